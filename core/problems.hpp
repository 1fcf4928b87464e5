#pragma once
// The test problems: vector fields g: G -> g of y' = y g(y) with their exact differentials
// dg_y(U) = d/dt g(y exp(tU)) at t = 0, given U and the tangent dy = d/dt y exp(tU) at t = 0 (the group's
// tangent(y, U): y U on a group of matrices under multiplication, U under addition).
// Each is written once on matrices; VectorFieldOf adapts it to a group's coordinates. A problem may add
// dg_matrix(group, y) for the groups whose basis it knows; the others assemble dg's matrix column by column.
#include <Eigen/Dense>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>

#include "groups/mechanics_groups.hpp"
#include "groups/so3_group.hpp"
#include "groups/son_group.hpp"
#include "heavy_top_params.hpp"
#include "options.hpp"
#include "rigid_body_params.hpp"

namespace lienewton {

template <class G>
class VectorField {
 public:
  using Element = typename G::Element;
  using Vector = typename G::Vector;
  using Operator = typename G::Operator;
  virtual ~VectorField() = default;
  virtual Vector g(const Element& y) const = 0;
  virtual Vector dg(const Element& y, const Vector& u) const = 0;
  // The time t at which g(t, y) is evaluated from now on. Integrators set it before each stage (t_k + c_i h);
  // solves leave it at 0. Built-in problems are autonomous and ignore it. A field belongs to one request, so
  // setting it is never shared between threads.
  virtual void set_time(double /*t*/) {}
  // The q x q matrix of dg_y on the coordinate basis; problems with sparse structure override the loop.
  virtual Operator dg_matrix(const G& group, const Element& y) const {
    Operator m = zero_operator(group);
    for (int i = 0; i < group.dim(); ++i) m.col(i) = dg(y, basis_vector(group, i));
    return m;
  }
};

// Index of the basis element E_ij - E_ji (i < j) in the paper's row-major order.
inline int pair_index(int n, int i, int j) { return i * (2 * n - i - 1) / 2 + (j - i - 1); }

// g(y) = diag(diag(y,1),1) - diag(diag(y,1),-1); linear in y, so dg_y(U) = g(yU).
struct PaperLinear {
  template <class M>
  M g(const M& y) const {
    M out = M::Zero(y.rows(), y.cols());
    for (Eigen::Index i = 0; i + 1 < y.rows(); ++i) {
      out(i, i + 1) = y(i, i + 1);
      out(i + 1, i) = -y(i, i + 1);
    }
    return out;
  }
  template <class M>
  M dg(const M&, const M&, const M& dy) const {
    return g(dy);
  }
  // On the basis of so(N): y b_ab = y_:a e_b^T - y_:b e_a^T has superdiagonal entries only at (b-1, b)
  // and (a-1, a), so each column has at most two entries.
  Eigen::MatrixXd dg_matrix(const SONGroup& group, const Eigen::MatrixXd& y) const {
    const int n = static_cast<int>(y.rows());
    Eigen::MatrixXd m = Eigen::MatrixXd::Zero(group.dim(), group.dim());
    for (int a = 0, col = 0; a < n; ++a)
      for (int b = a + 1; b < n; ++b, ++col) {
        m(pair_index(n, b - 1, b), col) += y(b - 1, a);
        if (a >= 1) m(pair_index(n, a - 1, a), col) -= y(a - 1, b);
      }
    return m;
  }
};

// U = sin.(y) (2y - 5y^2), g(y) = U - U^T; dg by the product rule along y' = y U_dir.
struct PaperSine {
  template <class M>
  M g(const M& y) const {
    const M u = y.array().sin().matrix() * (2.0 * y - 5.0 * y * y);
    return u - u.transpose();
  }
  template <class M>
  M dg(const M& y, const M&, const M& dy) const {
    const M s = y.array().sin().matrix();
    const M ds = (y.array().cos() * dy.array()).matrix();
    const M p = 2.0 * y - 5.0 * y * y;
    const M dp = 2.0 * dy - 5.0 * (dy * y + y * dy);
    const M du = ds * p + s * dp;
    return du - du.transpose();
  }
  // On the basis of so(N), dy = y b_ab = y_:a e_b^T - y_:b e_a^T has rank 2, so with s y and s y y formed once
  // every column of the product rule is a sum of outer products: O(N^2) per column instead of O(N^3).
  Eigen::MatrixXd dg_matrix(const SONGroup& group, const Eigen::MatrixXd& y) const {
    using Eigen::MatrixXd, Eigen::VectorXd;
    const int n = static_cast<int>(y.rows());
    const MatrixXd s = y.array().sin().matrix(), c = y.array().cos().matrix();
    const MatrixXd p = 2.0 * y - 5.0 * y * y;
    const MatrixXd sy = s * y, syy = sy * y;
    MatrixXd m(group.dim(), group.dim()), du(n, n);
    VectorXd ca_yb(n), cb_ya(n);
    for (int a = 0, col = 0; a < n; ++a)
      for (int b = a + 1; b < n; ++b, ++col) {
        // du = ds p + s dp with ds = cos.(y) .* dy and s dp = 2 s dy - 5 (s dy y + s y dy), column by column
        cb_ya = c.col(b).cwiseProduct(y.col(a));
        ca_yb = c.col(a).cwiseProduct(y.col(b));
        for (int j = 0; j < n; ++j)
          du.col(j) = cb_ya * p(b, j) - ca_yb * p(a, j) - 5.0 * (sy.col(a) * y(b, j) - sy.col(b) * y(a, j));
        du.col(b) += 2.0 * sy.col(a) - 5.0 * syy.col(a);
        du.col(a) -= 2.0 * sy.col(b) - 5.0 * syy.col(b);
        for (int i = 0, k = 0; i < n; ++i)
          for (int j = i + 1; j < n; ++j, ++k) m(k, col) = du(i, j) - du(j, i);
      }
    return m;
  }
};

// The free rigid body: y' = y hat(I^-1 y^T m), m the constant spatial angular momentum; the body momentum
// M = y^T m and the kinetic energy E = 1/2 M^T I^-1 M are conserved.
struct RigidBody {
  RigidBodyParams params;
  template <class M>
  M g(const M& y) const {
    return embed(body_velocity(Eigen::Matrix3d(y).transpose() * params.momentum));
  }
  template <class M>
  M dg(const M& y, const M& dir, const M&) const {  // d/dt of y^T m along y' = y dir (on SO(3)) is dir^T y^T m
    return embed(body_velocity(Eigen::Matrix3d(dir).transpose() * (Eigen::Matrix3d(y).transpose() * params.momentum)));
  }
  // In rotation-vector coordinates dg_y(u) = -I^-1 (u x M) = I^-1 hat(M) u with M = y^T m.
  Eigen::Matrix3d dg_matrix(const SO3Group&, const Eigen::Matrix3d& y) const {
    return params.inertia.cwiseInverse().asDiagonal() * so3::hat(y.transpose() * params.momentum);
  }
  double energy(const Eigen::Matrix3d& y) const {
    const Eigen::Vector3d m = y.transpose() * params.momentum;
    return 0.5 * m.dot(body_velocity(m));
  }

 private:
  Eigen::Vector3d body_velocity(const Eigen::Vector3d& m) const { return m.cwiseQuotient(params.inertia); }
  static Eigen::Matrix3d embed(const Eigen::Vector3d& w) { return so3::hat(w); }
};

// The heavy top on SO(3) x R^3 (heavy_top_params.hpp), its state the 7 x 7 block-diagonal
// y = [[R, 0], [0, [[I, w], [0, 1]]]] of SO3xR3Group: y' = y g(y) with
//   g(y) = [[hat(w), 0], [0, [[0, a], [0, 0]]]],  a = J^-1 ((J w) x w + m chi x (R^T gamma)),
// i.e. R' = R hat(w), w' = a, J the inertia about the pivot. Its energy 1/2 w^T J w - m gamma^T R chi is conserved,
// so is the vertical angular momentum e3^T R J w when gamma is vertical, and for a Lagrange top (chi on a principal
// axis k whose two other moments are equal) the spin w_k about that axis: (J w) x w and chi x (.) have no k part.
struct HeavyTop {
  HeavyTopParams params;
  Eigen::Matrix3d inertia;  // J about the pivot
  Eigen::Matrix3d inverse;  // J^-1

  explicit HeavyTop(const HeavyTopParams& p)
      : params(p), inertia(pivot_inertia(p)), inverse(inertia.inverse()) {}

  template <class M>
  M g(const M& y) const {
    const Eigen::Vector3d w = omega(y);
    return embed<M>(w, acceleration(rotation(y), w));
  }
  // Along y' = y dir, dir = hat(u_r, u_w): R' = R hat(u_r), w' = u_w, so (R^T gamma)' = -hat(u_r) R^T gamma
  // = (R^T gamma) x u_r, and a' = J^-1 ((J u_w) x w + (J w) x u_w + m chi x ((R^T gamma) x u_r)).
  template <class M>
  M dg(const M& y, const M& dir, const M&) const {
    const Eigen::Vector3d w = omega(y), u_r = so3::vee(rotation(dir)), u_w = omega(dir);
    const Eigen::Vector3d b = rotation(y).transpose() * params.gravity;
    const Eigen::Vector3d da = (inertia * u_w).cross(w) + (inertia * w).cross(u_w) +
                               params.mass * params.center.cross(b.cross(u_r));
    return embed<M>(u_w, inverse * da);
  }
  // The same on the coordinates (u_r, u_w): [[0, I], [J^-1 m hat(chi) hat(b), J^-1 (hat(J w) - hat(w) J)]].
  SO3xR3Group::Operator dg_matrix(const SO3xR3Group&, const SO3xR3Group::Element& y) const {
    const Eigen::Vector3d w = omega(y), b = rotation(y).transpose() * params.gravity;
    SO3xR3Group::Operator m = SO3xR3Group::Operator::Zero();
    m.topRightCorner<3, 3>().setIdentity();
    m.bottomLeftCorner<3, 3>() = inverse * (params.mass * so3::hat(params.center) * so3::hat(b));
    m.bottomRightCorner<3, 3>() = inverse * (so3::hat(inertia * w) - so3::hat(w) * inertia);
    return m;
  }
  template <class M>
  double energy(const M& y) const {
    const Eigen::Vector3d w = omega(y);
    return 0.5 * w.dot(inertia * w) - params.mass * params.gravity.dot(rotation(y) * params.center);
  }
  template <class M>
  double vertical_momentum(const M& y) const {
    return (rotation(y) * (inertia * omega(y))).z();
  }
  // The Lagrange top's symmetry axis k: chi along body axis k alone, the two other moments equal. None otherwise.
  std::optional<int> symmetry_axis() const {
    for (int k = 0; k < 3; ++k) {
      const int i = (k + 1) % 3, j = (k + 2) % 3;
      if (params.center(k) != 0.0 && params.center(i) == 0.0 && params.center(j) == 0.0 &&
          params.inertia(i) == params.inertia(j))
        return k;
    }
    return std::nullopt;
  }
  // The scales the invariants' drifts are measured against: the energy's kinetic and potential sizes, the norm of
  // the angular momentum J w (of which the vertical momentum is one component), and |w|.
  template <class M>
  double energy_scale(const M& y) const {
    const Eigen::Vector3d w = omega(y);
    return 0.5 * w.dot(inertia * w) + params.mass * params.gravity.norm() * params.center.norm();
  }
  template <class M>
  double momentum_scale(const M& y) const { return (inertia * omega(y)).norm(); }
  template <class M>
  static Eigen::Vector3d omega(const M& y) { return y.template block<3, 1>(3, 6); }
  // y(0): the state of (R(0), w(0)).
  Eigen::MatrixXd start() const {
    Eigen::MatrixXd y = Eigen::MatrixXd::Identity(7, 7);
    y.topLeftCorner<3, 3>() = params.rotation;
    y.block<3, 1>(3, 6) = params.omega;
    return y;
  }

 private:
  Eigen::Vector3d acceleration(const Eigen::Matrix3d& r, const Eigen::Vector3d& w) const {
    const Eigen::Vector3d torque = params.mass * params.center.cross(r.transpose() * params.gravity);
    return inverse * ((inertia * w).cross(w) + torque);
  }
  template <class M>
  static Eigen::Matrix3d rotation(const M& y) { return y.template topLeftCorner<3, 3>(); }
  // [[hat(w), 0], [0, [[0, a], [0, 0]]]]: the algebra element of (w, a).
  template <class M>
  static M embed(const Eigen::Vector3d& w, const Eigen::Vector3d& a) {
    M out = M::Zero(7, 7);
    out.template topLeftCorner<3, 3>() = so3::hat(w);
    out.template block<3, 1>(3, 6) = a;
    return out;
  }
};

template <class G, class Problem>
class VectorFieldOf final : public VectorField<G> {
 public:
  using typename VectorField<G>::Element;
  using typename VectorField<G>::Vector;
  VectorFieldOf(G group, Problem problem) : group_(group), problem_(std::move(problem)) {}
  Vector g(const Element& y) const override { return group_.vee(problem_.g(y)); }
  Vector dg(const Element& y, const Vector& u) const override {
    const Element dir = group_.hat(u);
    return group_.vee(problem_.dg(y, dir, Element(group_.tangent(y, dir))));
  }
  typename G::Operator dg_matrix(const G& group, const Element& y) const override {
    if constexpr (requires { problem_.dg_matrix(group, y); }) {  // the problem's structured matrix on G's basis
      return problem_.dg_matrix(group, y);
    } else {
      return VectorField<G>::dg_matrix(group, y);
    }
  }
  const Problem& problem() const { return problem_; }

 private:
  G group_;
  Problem problem_;
};

// The groups each problem is defined on (validate() checks before make_field). The paper's problems are matrix
// formulas with skew values: defined on every group of n x n matrices whose algebra holds the skew matrices
// (hat(vee(S)) = S for a skew S). rigid-body's formulas are 3 x 3 rotations': SO(3) alone; heavy-top's the
// 7 x 7 states of SO(3) x R^3.
template <class G>
bool algebra_holds_skew_matrices(const G& group) {
  Eigen::MatrixXd s = group.matrix(group.identity());
  for (Eigen::Index i = 0; i < s.rows(); ++i)
    for (Eigen::Index j = 0; j < s.cols(); ++j) s(i, j) = double(j - i);
  return group.matrix(group.hat(group.vee(group.element(s)))) == s;
}
// Where rigid-body's field compiles: its formulas take 3 x 3 matrices, so on groups of 3 x 3 or dynamic-size
// elements (SO(3) in closed form, and SO(N) at N = 3 by the spectral path, which the tests compare).
template <class G>
inline constexpr bool kTakesRigidBody =
    G::Element::RowsAtCompileTime == 3 || G::Element::RowsAtCompileTime == Eigen::Dynamic;
template <class G>
bool defined_on(ProblemKind kind, const G& group) {
  if (kind == ProblemKind::rigid_body) return std::is_same_v<G, SO3Group>;
  if (kind == ProblemKind::heavy_top) return std::is_same_v<G, SO3xR3Group>;
  return algebra_holds_skew_matrices(group);
}
// The one n a problem is written for, if any: rigid-body's and heavy-top's 3 (their group's index).
inline std::optional<int> required_index(ProblemKind kind) {
  if (kind == ProblemKind::rigid_body || kind == ProblemKind::heavy_top) return 3;
  return std::nullopt;
}
// The one group family a problem is written for, if any: heavy-top's SO(3) x R^3.
inline std::optional<std::string> required_group(ProblemKind kind) {
  if (kind == ProblemKind::heavy_top) return SOxRFamily::kName;
  return std::nullopt;
}

// The field of a request's problem on group G (one it is defined_on; validate() checks).
template <class G>
std::unique_ptr<VectorField<G>> make_field(const G& group, ProblemKind kind, const RigidBodyParams& rb,
                                           const HeavyTopParams& top = {}) {
  switch (kind) {
    case ProblemKind::paper_linear: return std::make_unique<VectorFieldOf<G, PaperLinear>>(group, PaperLinear{});
    case ProblemKind::paper_sine: return std::make_unique<VectorFieldOf<G, PaperSine>>(group, PaperSine{});
    case ProblemKind::rigid_body:
      if constexpr (kTakesRigidBody<G>) return std::make_unique<VectorFieldOf<G, RigidBody>>(group, RigidBody{rb});
      break;
    case ProblemKind::heavy_top:
      if constexpr (std::is_same_v<G, SO3xR3Group>)
        return std::make_unique<VectorFieldOf<G, HeavyTop>>(group, HeavyTop{top});
      break;
  }
  return nullptr;
}

}  // namespace lienewton
