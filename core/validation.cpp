#include "validation.hpp"

#include <cmath>

#include "group_registry.hpp"
#include "problems.hpp"

namespace lienewton::validation {

void check(const fields::NumberField& field, double x, const std::string& path) {
  if (!field.contains(x)) invalid(path, field.message(path));
}

void check(const fields::IntegerField& field, long long x, const std::string& path) {
  if (!field.contains(x)) invalid(path, field.message(path));
}

void check_problem_domain(const ProblemSpec& problem) {
  const GroupFamily& family = group_family(problem.group);
  const std::string name(to_string(problem.kind));
  const int n = required_index(problem.kind).value_or(problem.n);
  if (!family.defines(problem.kind, n)) unprocessable("group", name + " is not defined on " + family.title(problem.n));
  if (n != problem.n)
    unprocessable("n", name + " is a problem on " + family.title(n) + ": n must be " + std::to_string(n) + ", got " +
                           std::to_string(problem.n));
}

void check_rigid_body(const RigidBodyParams& p) {
  if (!p.inertia.allFinite() || (p.inertia.array() <= 0.0).any())
    invalid("rigid_body.inertia", "rigid_body.inertia must be three finite positive numbers");
  if (!p.momentum.allFinite()) invalid("rigid_body.momentum", "rigid_body.momentum must be three finite numbers");
}

void check_start_point(const ProblemSpec& problem) {
  const auto& z = problem.z;
  if (!z) return;
  const int n = problem.n;
  if (z->rows() != n || z->cols() != n) invalid("z", "z must be an n x n array of rows");
  if (!z->allFinite()) invalid("z", "z must have finite entries");
  const std::string why = group_family(problem.group).not_an_element(n, *z, "z");
  if (!why.empty()) unprocessable("z", why);
}

void check_start_guess(const ProblemSpec& problem, const Eigen::MatrixXd& y0) {
  const Eigen::MatrixXd z = problem.start();
  const auto n = z.rows();
  if (y0.rows() != n || y0.cols() != n) invalid("y0", "y0 must be an n x n array of rows");
  if (!y0.allFinite()) invalid("y0", "y0 must have finite entries");
  const GroupFamily& family = group_family(problem.group);
  std::string why = family.not_an_element(problem.n, y0, "y0");
  if (why.empty()) why = family.not_reachable(problem.n, y0, z);
  if (!why.empty()) unprocessable("y0", why);
}

}  // namespace lienewton::validation
