#pragma once
// What a request solves: the test problem on a group (SO(n) by default), its parameters and the start point z
// (the group's random element from seed when absent). Shared by solve, sweep, integrate and work-precision.
#include <Eigen/Dense>
#include <cstdint>
#include <optional>
#include <string>

#include "chain_params.hpp"
#include "heavy_top_params.hpp"
#include "options.hpp"
#include "program_cache.hpp"
#include "rigid_body_params.hpp"
#include "spec_cache.hpp"
#include "stiff_body_params.hpp"
#include "user_field/program.hpp"

namespace lienewton {

struct ProblemSpec {
  ProblemKind kind = ProblemKind::paper_linear;
  std::string group = "SO";  // the Lie group by its registered name; n is its index, as in SO(n)
  int n = 3;
  std::uint64_t seed = 1;
  // start point; when absent, the group's random element from seed (heavy-top, stiff-body: the state of their
  // parameters' rotation and omega, which give their start instead of z; chain: its straight start at chain.tilt)
  std::optional<Eigen::MatrixXd> z{};
  RigidBodyParams rigid_body{};
  HeavyTopParams heavy_top{};
  StiffBodyParams stiff_body{};
  ChainParams chain{};
  // The user's own field g(y) as a program (user_field/program.hpp), used instead of kind; the named numbers and
  // matrices it reads.
  std::optional<std::string> g{};
  user_field::Parameters parameters{};
  // g compiled per matrix size, shared with this spec's copies: compiled once per request and n.
  std::shared_ptr<ProgramCache> programs = std::make_shared<ProgramCache>();
  // The family group names and the seeded start, resolved once and shared with this spec's copies.
  std::shared_ptr<SpecCache> resolved = std::make_shared<SpecCache>();

  // Whether the request's field is the built-in problem `k` (not a user's program).
  bool is(ProblemKind k) const { return !g && kind == k; }
  // The field's name in titles and reasons: the built-in problem's, or "g(y)".
  std::string name() const;

  // g compiled for n (from `programs`); throws RequestError naming g. Only for a spec with g.
  std::shared_ptr<const user_field::Program> program() const;

  // The family `group` names (from `resolved`); throws RequestError naming group when none is registered.
  const GroupFamily& family() const { return resolved->family(group); }

  // z, or heavy-top's, stiff-body's or chain's start, or the seeded random start point when z is absent.
  Eigen::MatrixXd start() const;
};

// Checks n, the group, that the problem is defined on it, the problem's parameters and z, and compiles a user's
// program g (its errors name the line and column) and checks that g(z) lies in the group's algebra; throws
// RequestError. threads: how many threads evaluate g at once (the workspace budget counts each).
void validate(const ProblemSpec& problem, int threads = 1);
// ProblemSpecs validated in this process: tests count them per request.
std::uint64_t problem_validations();

}  // namespace lienewton
