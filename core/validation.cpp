#include "validation.hpp"

#include <cmath>
#include <utility>

#include "group_registry.hpp"
#include "user_field/algebra_defect.hpp"
#include "problems.hpp"
#include "request_error.hpp"
#include "user_field/program.hpp"

namespace lienewton::validation {

void check(const fields::NumberField& field, double x, const std::string& path) {
  if (!field.contains(x)) invalid(path, field.message(path));
}

void check(const fields::IntegerField& field, long long x, const std::string& path) {
  if (!field.contains(x)) invalid(path, field.message(path));
}

void check_tolerance(const fields::NumberField& field, double x, const std::string& path) {
  if (!field.contains(x)) unprocessable(path, field.message(path));
}

void check_problem_domain(const ProblemSpec& problem) {
  const GroupFamily& family = problem.family();
  if (const std::optional<int> only = family.only_index(); only && *only != problem.n)
    unprocessable("n", "the group " + problem.group + " has one member, " + family.title(*only) + ": n must be " +
                           std::to_string(*only) + ", got " + std::to_string(problem.n));
  if (problem.g) return;  // a user's program is compiled for the request's n on any group (check_user_field)
  const std::string name(to_string(problem.kind));
  const int n = required_index(problem.kind).value_or(problem.n);
  if (const std::optional<std::string> only = required_group(problem.kind); only && *only != problem.group)
    unprocessable("group", name + " is a problem on " + group_family(*only).title(n) + ": group must be " + *only);
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

void check_heavy_top(const ProblemSpec& problem) {
  const HeavyTopParams& p = problem.heavy_top;
  const auto bounded = [](const auto& x) { return x.allFinite() && x.cwiseAbs().maxCoeff() <= HeavyTopParams::kBound; };
  const std::string bound = fields::format_bound(HeavyTopParams::kBound);
  if (!(p.mass > 0.0 && p.mass <= HeavyTopParams::kBound))
    unprocessable("heavy_top.mass", "heavy_top.mass must be a finite number in (0, " + bound + "]");
  if (!bounded(p.inertia) || (p.inertia.array() <= 0.0).any())
    unprocessable("heavy_top.inertia", "heavy_top.inertia must be three positive numbers, at most " + bound);
  using Named = std::pair<const char*, const Eigen::Vector3d*>;
  for (const auto& [name, v] : {Named{"center", &p.center}, Named{"gravity", &p.gravity}, Named{"omega", &p.omega}})
    if (!bounded(*v))
      unprocessable(std::string("heavy_top.") + name,
                    std::string("heavy_top.") + name + " must be three finite numbers, at most " + bound + " in size");
  if (!p.rotation.allFinite())
    unprocessable("heavy_top.rotation", "heavy_top.rotation must be a 3 x 3 rotation of finite numbers");
  if (std::string why = group_family("SO").not_an_element(3, p.rotation, "heavy_top.rotation"); !why.empty())
    unprocessable("heavy_top.rotation", why);
  if (p.rotation.determinant() < 0.0)
    unprocessable("heavy_top.rotation", "heavy_top.rotation must be a rotation (det +1), not a reflection");
  if (problem.is(ProblemKind::heavy_top) && problem.z)
    unprocessable("z", "heavy-top starts at heavy_top.rotation and heavy_top.omega: give those instead of z");
}

void check_workspace(const ProblemSpec& problem, int threads) {
  if (!problem.g) return;
  const double bytes = problem.program()->workspace_bytes(problem.family().algebra_dim(problem.n)) * threads;
  if (bytes > user_field::kMaxWorkspaceBytes)
    throw RequestError(RequestError::Kind::too_large, "g",
                       "g's evaluation would hold " + std::to_string(static_cast<long long>(bytes / (1 << 20))) +
                           " MiB of workspace (" + std::to_string(threads) + " thread" + (threads == 1 ? "" : "s") +
                           "), more than the limit of " +
                           std::to_string(static_cast<long long>(user_field::kMaxWorkspaceBytes / (1 << 20))) +
                           " MiB per request: use smaller intermediate values" + (threads > 1 ? " or fewer threads" : ""));
}

void check_user_field(const ProblemSpec& problem, int threads) {
  if (!problem.g) {
    if (!problem.parameters.empty()) unprocessable("parameters", "parameters are read by a program: give g too");
    return;
  }
  if (problem.parameters.size() > user_field::kMaxParameters)
    invalid("parameters", "at most " + std::to_string(user_field::kMaxParameters) + " parameters");
  for (const auto& [name, value] : problem.parameters) user_field::check_parameter(name, value);
  const GroupFamily& family = problem.family();
  const auto program = problem.program();
  check_workspace(problem, threads);
  // A program whose value at the start is off the algebra is wrong everywhere in practice: say so before solving,
  // when one evaluation is cheap (a sweep validates every n); otherwise the run's own check names g.
  constexpr double kCheapFlops = 1e8;
  if (program->cost() > kCheapFlops) return;
  const Eigen::MatrixXd z = problem.start();
  Eigen::MatrixXd value;
  program->eval(z, 0.0, value);
  const double defect = family.algebra_defect(problem.n, value);
  if (std::isfinite(defect) && !within_rounding(defect, value))
    unprocessable("g", "g(y) must lie in the algebra of " + family.title(problem.n) + " (on SO(n): skew, g' = -g); at "
                       "y = z, t = 0, ||g - hat(vee(g))|| = " + std::to_string(defect) + ": write g = u - u' or g = skew(u)");
}

void check_start_point(const ProblemSpec& problem) {
  const auto& z = problem.z;
  if (!z) return;
  const int n = problem.n, size = problem.family().matrix_size(n);
  if (z->rows() != size || z->cols() != size)
    invalid("z", size == n ? "z must be an n x n array of rows" : "z must be a " + std::to_string(size) + " x " +
                                                                     std::to_string(size) + " array of rows");
  if (!z->allFinite()) invalid("z", "z must have finite entries");
  const std::string why = problem.family().not_an_element(n, *z, "z");
  if (!why.empty()) unprocessable("z", why);
}

void check_start_guess(const ProblemSpec& problem, const Eigen::MatrixXd& y0) {
  const Eigen::MatrixXd z = problem.start();
  const auto n = z.rows();
  if (y0.rows() != n || y0.cols() != n)
    invalid("y0", "y0 must be a " + std::to_string(n) + " x " + std::to_string(n) + " array of rows (z's size)");
  if (!y0.allFinite()) invalid("y0", "y0 must have finite entries");
  const GroupFamily& family = problem.family();
  std::string why = family.not_an_element(problem.n, y0, "y0");
  if (why.empty()) why = family.not_reachable(problem.n, y0, z);
  if (!why.empty()) unprocessable("y0", why);
}

}  // namespace lienewton::validation
