#pragma once
// What a ProblemSpec resolves from its fields once and shares with its copies, as ProgramCache does: the group's
// family, looked up by name, and the seeded start point. Each is keyed by the fields it depends on, so a copy that
// changes them (a sweep's dimensions change n) resolves its own instead of reading a stale one.
#include <Eigen/Dense>
#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

namespace lienewton {

class GroupFamily;

class SpecCache {
 public:
  // The family `group` names; throws RequestError (field "group") as group_family does, and caches nothing then.
  const GroupFamily& family(const std::string& group);
  // The family's random element of index n from seed: drawn on first use, then the same matrix.
  Eigen::MatrixXd seeded_start(const GroupFamily& family, int n, std::uint64_t seed);

  // Seeded starts drawn through any cache in this process: tests count them per request.
  static std::uint64_t seeded_starts() { return seeded_starts_.load(); }

 private:
  struct Start {
    const GroupFamily* family;
    int n;
    std::uint64_t seed;
    Eigen::MatrixXd y;
  };
  std::mutex mutex_;
  std::string group_;
  const GroupFamily* family_ = nullptr;
  std::vector<Start> starts_;
  static inline std::atomic<std::uint64_t> seeded_starts_{0};
};

}  // namespace lienewton
