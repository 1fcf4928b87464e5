// The cancellation token: its three causes, the ambient scope, its hand-over to parallel_for's workers, and
// the loops that poll it (the reference solution throws Cancelled, a solver ends with Status::cancelled).
#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <thread>

#include "core/cancellation.hpp"
#include "core/gmres.hpp"
#include "core/parallel_for.hpp"
#include "core/reference_solution.hpp"
#include "core/start_point.hpp"

namespace lienewton {
namespace {

using Clock = CancellationToken::Clock;

TEST(Cancellation, EachCauseCancelsAndTheFirstReasonStays) {
  std::atomic<bool> shutdown{false};
  auto gone = std::make_shared<std::atomic<bool>>(false);
  const CancellationToken token(Clock::now() + std::chrono::hours(1), &shutdown, gone);
  EXPECT_FALSE(token.cancelled());
  gone->store(true);
  EXPECT_TRUE(token.cancelled());
  EXPECT_EQ(token.reason(), CancelReason::client_gone);
  shutdown = true;
  EXPECT_EQ(token.reason(), CancelReason::client_gone);

  const CancellationToken stopping(Clock::now() + std::chrono::hours(1), &shutdown, nullptr);
  EXPECT_TRUE(stopping.cancelled());
  EXPECT_EQ(stopping.reason(), CancelReason::shutdown);

  const CancellationToken late(Clock::now() - std::chrono::seconds(1), nullptr, nullptr);
  EXPECT_TRUE(late.cancelled());
  EXPECT_EQ(late.reason(), CancelReason::deadline);

  const CancellationToken never;
  EXPECT_FALSE(never.cancelled());
}

TEST(Cancellation, ScopeIsPerThreadAndNests) {
  const CancellationToken late(Clock::now() - std::chrono::seconds(1), nullptr, nullptr);
  EXPECT_FALSE(cancellation_requested());
  {
    const CancellationScope outer(&late);
    EXPECT_TRUE(cancellation_requested());
    bool other_thread = true;
    std::thread([&] { other_thread = cancellation_requested(); }).join();
    EXPECT_FALSE(other_thread);
    {
      const CancellationScope inner(nullptr);
      EXPECT_FALSE(cancellation_requested());
    }
    EXPECT_TRUE(cancellation_requested());
  }
  EXPECT_FALSE(cancellation_requested());
}

TEST(Cancellation, ParallelForWorkersSeeTheCallersToken) {
  const CancellationToken late(Clock::now() - std::chrono::seconds(1), nullptr, nullptr);
  const CancellationScope scope(&late);
  std::atomic<int> seen{0};
  parallel_for(8, 4, [&](int) {
    if (cancellation_requested()) ++seen;
    return true;
  });
  EXPECT_EQ(seen.load(), 8);
}

TEST(Cancellation, ReferenceSolutionStopsAtOnce) {
  const Eigen::MatrixXd y0 = start_point(8, 1);
  const CancellationToken late(Clock::now() - std::chrono::seconds(1), nullptr, nullptr);
  const CancellationScope scope(&late);
  EXPECT_THROW(reference_solution(ProblemSpec{.kind = ProblemKind::paper_sine, .n = 8}, y0, 100.0), Cancelled);
}

// GMRES polls inside its Arnoldi loop: a token cancelled during the third application of A stops it before the
// fourth, where the system (diag(1..400), rtol 1e-14) would otherwise need hundreds of steps.
TEST(Cancellation, GmresStopsInsideItsArnoldiLoop) {
  std::atomic<bool> shutdown{false};
  const CancellationToken token(Clock::time_point::max(), &shutdown, nullptr);
  const CancellationScope scope(&token);
  const Eigen::VectorXd diagonal = Eigen::VectorXd::LinSpaced(400, 1.0, 400.0);
  int applications = 0;
  auto apply = [&](const Eigen::VectorXd& v) {
    if (++applications == 3) shutdown = true;
    return Eigen::VectorXd(diagonal.cwiseProduct(v));
  };
  Eigen::VectorXd x;
  EXPECT_THROW(gmres(apply, Eigen::VectorXd::Ones(400), x, 1e-14, 300), Cancelled);
  EXPECT_EQ(applications, 3);
}

}  // namespace
}  // namespace lienewton
