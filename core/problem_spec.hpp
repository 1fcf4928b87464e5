#pragma once
// What a request solves: the test problem on SO(n), its parameters and the start point z (drawn from seed when
// absent). Shared by solve, sweep, integrate and work-precision.
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
  std::optional<Eigen::MatrixXd> z{};  // start point; when absent, start_point(n, seed)
  RigidBodyParams rigid_body{};

  // z, or the seeded random start point when z is absent.
  Eigen::MatrixXd start() const;
};

// Checks n, that the problem is defined on SO(n), the problem's parameters and z; throws RequestError.
void validate(const ProblemSpec& problem);

}  // namespace lienewton
