#pragma once
// What a request solves: the test problem on a group (SO(n) by default), its parameters and the start point z
// (the group's random element from seed when absent). Shared by solve, sweep, integrate and work-precision.
#include <Eigen/Dense>
#include <cstdint>
#include <optional>
#include <string>

#include "options.hpp"
#include "rigid_body_params.hpp"

namespace lienewton {

struct ProblemSpec {
  ProblemKind kind = ProblemKind::paper_linear;
  std::string group = "SO";  // the Lie group by its registered name; n is its index, as in SO(n)
  int n = 3;
  std::uint64_t seed = 1;
  std::optional<Eigen::MatrixXd> z{};  // start point; when absent, the group's random element from seed
  RigidBodyParams rigid_body{};

  // z, or the seeded random start point when z is absent.
  Eigen::MatrixXd start() const;
};

// Checks n, the group, that the problem is defined on it, the problem's parameters and z; throws RequestError.
void validate(const ProblemSpec& problem);

}  // namespace lienewton
