// parallel_for: the claim order it is given, every item exactly once, any thread count.
#include "core/parallel_for.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <vector>

namespace lienewton {
namespace {

TEST(ParallelFor, OneThreadClaimsItemsInTheGivenOrder) {
  std::vector<int> seen;
  parallel_for(4, 1, [&](int i) { seen.push_back(i); return true; }, {3, 1, 0, 2});
  EXPECT_EQ(seen, (std::vector<int>{3, 1, 0, 2}));
}

TEST(ParallelFor, EveryItemRunsOnceForAnyThreadCountAndOrder) {
  const std::vector<int> order{5, 4, 3, 2, 1, 0};
  for (int threads : {1, 2, 5}) {
    std::vector<std::atomic<int>> runs(6);
    parallel_for(6, threads, [&](int i) { ++runs[static_cast<std::size_t>(i)]; return true; }, order);
    for (const auto& r : runs) EXPECT_EQ(r.load(), 1) << threads << " threads";
  }
}

TEST(ParallelFor, RefusesAnOrderOfTheWrongLength) {
  EXPECT_THROW(parallel_for(3, 1, [](int) { return true; }, {0, 1}), std::invalid_argument);
}

}  // namespace
}  // namespace lienewton
