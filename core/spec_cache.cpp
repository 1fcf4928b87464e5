#include "spec_cache.hpp"

#include "group_registry.hpp"

namespace lienewton {

const GroupFamily& SpecCache::family(const std::string& group) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (family_ && group_ == group) return *family_;
  const GroupFamily& found = group_family(group);
  group_ = group;
  family_ = &found;
  return found;
}

Eigen::MatrixXd SpecCache::seeded_start(const GroupFamily& family, int n, std::uint64_t seed) {
  // Drawn under the lock: threads that need the same start wait for it instead of drawing it again.
  const std::lock_guard<std::mutex> lock(mutex_);
  for (const Start& s : starts_)
    if (s.family == &family && s.n == n && s.seed == seed) return s.y;
  Eigen::MatrixXd y = family.random(n, seed);
  seeded_starts_.fetch_add(1);
  starts_.push_back({&family, n, seed, y});
  return y;
}

}  // namespace lienewton
