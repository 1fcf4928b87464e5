#pragma once
// The groups a request may name: "group": "SO" picks the family SO and n its member SO(n). Each family is
// registered once, by register_group<Family>() (register_group.hpp), which compiles the request code for its
// groups; the requests reach a group only through the family found here by name (a ProblemSpec resolves its
// group once: ProblemSpec::family()).
#include <Eigen/Dense>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "basins.hpp"
#include "groups/body_frame.hpp"
#include "integrate.hpp"
#include "reference_solution.hpp"
#include "solve.hpp"

namespace lienewton {

// One registered family of groups, indexed by n, with every request it answers; n is valid (fields::n) and the
// matrices have been checked for shape and membership before these are called.
// Rows and columns of a group's matrices.
struct MatrixShape {
  int rows, cols;
  bool square() const { return rows == cols; }
  std::string text() const { return std::to_string(rows) + " x " + std::to_string(cols); }  // "11 x 88"
  friend bool operator==(const MatrixShape&, const MatrixShape&) = default;
};

class GroupFamily {
 public:
  virtual ~GroupFamily() = default;
  virtual std::string name() const = 0;         // as a request names it: "SO"
  virtual std::string title(int n) const = 0;   // as a title names its member: "SO(3)"
  // The index of the family's one member, if it has only one (SE: 3); validation checks n before anything else.
  virtual std::optional<int> only_index() const = 0;
  // The largest index the family takes, if it bounds n itself (SExR^k: 128 bodies); validation checks it, and the
  // server's --max-n cap (meant for SO(N)'s dense N) does not apply to such a family.
  virtual std::optional<int> max_index() const = 0;
  // The shape of its member's matrices (n x n on SO(n), (n + 1) x (n + 1) on SE(n), 11 x 11k on (SE(3) x R^6)^k,
  // the bodies side by side): a request's z and y0 have that shape.
  virtual MatrixShape matrix_shape(int n) const = 0;
  virtual int algebra_dim(int n) const = 0;
  virtual std::string algebra_dimension() const = 0;  // algebra_dim as a formula in n: "n(n-1)/2"
  virtual double log_radius() const = 0;
  virtual bool defines(ProblemKind kind, int n) const = 0;  // the problem is defined on the group (problems.hpp)
  virtual Eigen::MatrixXd random(int n, std::uint64_t seed) const = 0;  // the seeded start
  // Why a request's matrix `name` (matrix_shape, finite) is refused as an element, or why y0 cannot be reached from z;
  // empty when accepted.
  virtual std::string not_an_element(int n, const Eigen::MatrixXd& m, const std::string& name) const = 0;
  virtual std::string not_reachable(int n, const Eigen::MatrixXd& y0, const Eigen::MatrixXd& z) const = 0;
  virtual Eigen::MatrixXd project(int n, const Eigen::MatrixXd& m) const = 0;  // the element nearest to m
  virtual bool same_root(int n, const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) const = 0;  // basin_map.hpp
  // What a user's program reads for the element m (matrix_shape): m itself, or a system of bodies' diag(y1, ..., yk)
  // (user_field/algebra_defect.hpp); its size, program_size(n), is what a program is compiled for.
  virtual Eigen::MatrixXd program_matrix(int n, const Eigen::MatrixXd& m) const = 0;
  virtual int program_size(int n) const = 0;
  // ||hat(vee(m)) - m||: how far a program's value m is from the algebra (a user's g must lie in it).
  virtual double algebra_defect(int n, const Eigen::MatrixXd& m) const = 0;
  // The bodies of an element (matrix_shape) as pictures draw them: a group with one rotation part gives one
  // frame at the origin (SO(3): y itself; SE(3): R of [[R, p], [0, 1]]; SO(3) x R^3: its R), a system of bodies
  // each body's axes at its position ((SE(3) x R^6)^k), the other groups none.
  virtual std::vector<BodyFrame> body_frames(int n, const Eigen::MatrixXd& m) const = 0;

  // The requests on the group (validated by their callers).
  virtual SolveResult solve(const SolveRequest& request, const TraceCallback& on_iteration) const = 0;
  virtual BasinResult basins(const BasinRequest& request, const BasinRowCallback& on_row,
                             const WorkFarm* farm) const = 0;
  virtual IntegrateResult integrate(const IntegrateRequest& request, const Eigen::MatrixXd& y0,
                                    const StepCallback& on_step) const = 0;
  virtual ReferenceSolution reference_solution(const ProblemSpec& problem, const Eigen::MatrixXd& y0,
                                               double t_end) const = 0;
  // max(||g(y)||, ||dg_y||_F) of the problem's field (time_scale.hpp).
  virtual double field_rate(const ProblemSpec& problem, const Eigen::MatrixXd& y) const = 0;
};

// The family a request names; throws RequestError (unprocessable, field "group") listing the registered names.
const GroupFamily& group_family(const std::string& name);
// Every registered name, in registration order ("SO" first).
std::vector<std::string> registered_group_names();
// Adds a family (register_group.hpp); a name registered twice is a programming error (std::logic_error).
void add_group_family(std::unique_ptr<GroupFamily> family);

}  // namespace lienewton
