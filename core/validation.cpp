#include "validation.hpp"

#include <cmath>
#include <numbers>
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
  if (const std::optional<int> max = family.max_index(); max && problem.n > *max)
    unprocessable("n", "the group " + problem.group + " takes n from " + std::to_string(fields::n.min) + " to " +
                           std::to_string(*max) + " (" + family.title(*max) + " is the largest), got " +
                           std::to_string(problem.n));
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

namespace {

// Each entry finite and at most bound in size.
bool bounded(const Eigen::Vector3d& x, double bound) { return x.allFinite() && x.cwiseAbs().maxCoeff() <= bound; }

// A parameter that must be three finite numbers within bound (422 naming path).
void check_vector(const Eigen::Vector3d& x, double bound, const std::string& path) {
  if (!bounded(x, bound))
    unprocessable(path, path + " must be three finite numbers, at most " + fields::format_bound(bound) + " in size");
}

// A parameter that must be three positive numbers within bound (principal moments).
void check_moments(const Eigen::Vector3d& x, double bound, const std::string& path) {
  if (!bounded(x, bound) || (x.array() <= 0.0).any())
    unprocessable(path, path + " must be three positive numbers, at most " + fields::format_bound(bound));
}

// R(0) of a problem on SO(3) x R^3: a rotation of finite numbers, orthogonal to SO's tolerance, det +1.
void check_rotation(const Eigen::Matrix3d& r, const std::string& path) {
  if (!r.allFinite()) unprocessable(path, path + " must be a 3 x 3 rotation of finite numbers");
  if (std::string why = group_family("SO").not_an_element(3, r, path); !why.empty()) unprocessable(path, why);
  if (r.determinant() < 0.0) unprocessable(path, path + " must be a rotation (det +1), not a reflection");
}

// The problem's start is its parameters' (R(0), w(0)): a z as well is refused.
void refuse_z(const ProblemSpec& problem, ProblemKind kind, const std::string& params) {
  if (problem.is(kind) && problem.z)
    unprocessable("z", std::string(to_string(kind)) + " starts at " + params + ".rotation and " + params +
                           ".omega: give those instead of z");
}

}  // namespace

void check_heavy_top(const ProblemSpec& problem) {
  const HeavyTopParams& p = problem.heavy_top;
  constexpr double bound = HeavyTopParams::kBound;
  if (!(p.mass > 0.0 && p.mass <= bound))
    unprocessable("heavy_top.mass",
                  "heavy_top.mass must be a finite number in (0, " + fields::format_bound(bound) + "]");
  check_moments(p.inertia, bound, "heavy_top.inertia");
  using Named = std::pair<const char*, const Eigen::Vector3d*>;
  for (const auto& [name, v] : {Named{"center", &p.center}, Named{"gravity", &p.gravity}, Named{"omega", &p.omega}})
    check_vector(*v, bound, std::string("heavy_top.") + name);
  check_rotation(p.rotation, "heavy_top.rotation");
  refuse_z(problem, ProblemKind::heavy_top, "heavy_top");
}

void check_stiff_body(const ProblemSpec& problem) {
  const StiffBodyParams& p = problem.stiff_body;
  constexpr double bound = StiffBodyParams::kBound;
  const std::string text = fields::format_bound(bound);
  if (!(p.k > 0.0 && p.k <= bound))
    unprocessable("stiff_body.k", "stiff_body.k must be a finite number in (0, " + text + "]");
  if (p.c && !(*p.c >= 0.0 && *p.c <= bound))
    unprocessable("stiff_body.c", "stiff_body.c must be a finite number in [0, " + text + "]");
  check_moments(p.J, bound, "stiff_body.J");
  check_vector(p.f, bound, "stiff_body.f");
  check_rotation(p.rotation, "stiff_body.rotation");
  check_vector(p.omega, bound, "stiff_body.omega");
  refuse_z(problem, ProblemKind::stiff_body, "stiff_body");
}

void check_chain(const ProblemSpec& problem) {
  const ChainParams& p = problem.chain;
  constexpr double bound = ChainParams::kBound;
  const std::string text = fields::format_bound(bound);
  using Named = std::pair<const char*, double>;
  for (const auto& [name, x] : {Named{"mass", p.mass}, Named{"length", p.length}})
    if (!(x > 0.0 && x <= bound))
      unprocessable(std::string("chain.") + name, std::string("chain.") + name + " must be a finite number in (0, " +
                                                      text + "]");
  for (const auto& [name, x] : {Named{"stiffness", p.stiffness}, Named{"damping", p.damping}})
    if (!(x >= 0.0 && x <= bound))
      unprocessable(std::string("chain.") + name, std::string("chain.") + name + " must be a finite number in [0, " +
                                                      text + "]");
  check_moments(p.inertia, bound, "chain.inertia");
  check_vector(p.gravity, bound, "chain.gravity");
  if (!(std::abs(p.tilt) <= std::numbers::pi))
    unprocessable("chain.tilt", "chain.tilt must be a finite angle in [-pi, pi] (radians)");
  if (problem.is(ProblemKind::chain) && problem.z)
    unprocessable("z", "chain starts straight and at rest, turned by chain.tilt: give that instead of z");
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
  const Eigen::MatrixXd z = family.program_matrix(problem.n, problem.start());
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
  const int n = problem.n;
  const MatrixShape shape = problem.family().matrix_shape(n);
  if (z->rows() != shape.rows || z->cols() != shape.cols)
    invalid("z", shape == MatrixShape{n, n} ? "z must be an n x n array of rows"
                                            : "z must be a " + shape.text() + " array of rows");
  if (!z->allFinite()) invalid("z", "z must have finite entries");
  const std::string why = problem.family().not_an_element(n, *z, "z");
  if (!why.empty()) unprocessable("z", why);
}

void check_start_guess(const ProblemSpec& problem, const Eigen::MatrixXd& y0) {
  const Eigen::MatrixXd z = problem.start();
  if (y0.rows() != z.rows() || y0.cols() != z.cols())
    invalid("y0", "y0 must be a " + std::to_string(z.rows()) + " x " + std::to_string(z.cols()) +
                      " array of rows (z's size)");
  if (!y0.allFinite()) invalid("y0", "y0 must have finite entries");
  const GroupFamily& family = problem.family();
  std::string why = family.not_an_element(problem.n, y0, "y0");
  if (why.empty()) why = family.not_reachable(problem.n, y0, z);
  if (!why.empty()) unprocessable("y0", why);
}

}  // namespace lienewton::validation
