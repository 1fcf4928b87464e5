#pragma once
// Field checks shared by every request type; each throws RequestError naming the field.
#include <Eigen/Dense>
#include <optional>
#include <string>

#include "fields.hpp"
#include "options.hpp"
#include "problem_spec.hpp"
#include "request_error.hpp"
#include "rigid_body_params.hpp"

namespace lienewton::validation {

[[noreturn]] inline void invalid(const std::string& field, const std::string& message) {
  throw RequestError(RequestError::Kind::invalid, field, message);
}
[[noreturn]] inline void unprocessable(const std::string& field, const std::string& message) {
  throw RequestError(RequestError::Kind::unprocessable, field, message);
}

// A field of the table in fields.hpp; path names it in the error (e.g. "n", "cells[2].h").
void check(const fields::NumberField& field, double x, const std::string& path);
void check(const fields::IntegerField& field, long long x, const std::string& path);
// A tolerance of adaptive steps (rtol, atol, tolerances): a finite number in (0, 1], else 422 naming path. The
// codec reads any finite number: a tolerance outside the range is well-formed, but nothing can meet it.
void check_tolerance(const fields::NumberField& field, double x, const std::string& path);
// The problem's group is registered, has a member of index n, and the problem is defined on it (group_registry.hpp, problems.hpp).
void check_problem_domain(const ProblemSpec& problem);
void check_rigid_body(const RigidBodyParams& params);
// heavy_top's parameters (422 naming e.g. heavy_top.mass): mass and inertia positive, every entry finite and at most
// HeavyTopParams::kBound in size, rotation a rotation; and no z for heavy-top, whose start they give.
void check_heavy_top(const ProblemSpec& problem);
// stiff_body's parameters (422 naming e.g. stiff_body.k): k positive, c (when given) non-negative, J positive, every
// number finite and at most StiffBodyParams::kBound in size, rotation a rotation; and no z for stiff-body.
void check_stiff_body(const ProblemSpec& problem);
// chain's parameters (422 naming e.g. chain.length): mass, length and inertia positive, stiffness and damping
// non-negative, every number finite and at most ChainParams::kBound in size, |tilt| <= pi; and no z for chain.
void check_chain(const ProblemSpec& problem);
// A user's program g: parameters well-named and finite, the program compiled for n (RequestError with its line
// and column), its workspace on `threads` threads within user_field::kMaxWorkspaceBytes (413 naming g), g(z) in
// the group's algebra; parameters without g are refused.
void check_user_field(const ProblemSpec& problem, int threads = 1);
// A valid problem's program within user_field::kMaxWorkspaceBytes of workspace on `threads` evaluating threads
// (413 naming g); nothing for a built-in problem. For requests that validate the problem for one thread first.
void check_workspace(const ProblemSpec& problem, int threads);
// The problem's z, when given: the group's square size (n on SO(n)), finite and an element of the group (its not_an_element).
void check_start_point(const ProblemSpec& problem);
// y0, the iteration's start: z's size, finite, an element of the group and reachable from the problem's z (on SO(N):
// orthogonal to 1e-10 and det y0 = det z, so that z^-1 y0 is a rotation). Throws RequestError naming "y0".
void check_start_guess(const ProblemSpec& problem, const Eigen::MatrixXd& y0);

}  // namespace lienewton::validation
