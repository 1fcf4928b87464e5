#pragma once
// The test problems: vector fields g: G -> g of y' = y g(y) with their exact differentials
// dg_y(U) = d/dt g(y exp(tU)) at t = 0, given U and the tangent dy = d/dt y exp(tU) at t = 0 (the group's
// tangent(y, U): y U on a group of matrices under multiplication, U under addition).
// Each is written once on matrices; VectorFieldOf adapts it to a group's coordinates. A problem may add
// dg_matrix(group, y) for the groups whose basis it knows; the others assemble dg's matrix column by column.
#include <Eigen/Dense>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>

#include "chain.hpp"
#include "groups/mechanics_groups.hpp"
#include "groups/so3_group.hpp"
#include "groups/son_group.hpp"
#include "heavy_top_params.hpp"
#include "options.hpp"
#include "rigid_body_params.hpp"
#include "so3xr3_state.hpp"
#include "stiff_body_params.hpp"

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
  // solves leave it at 0. The built-in problems but stiff-body (its forcing f(t)) are autonomous and ignore it. A
  // field belongs to one request, so setting it is never shared between threads.
  virtual void set_time(double /*t*/) {}
  // The q x q matrix of dg_y on the coordinate basis; problems with sparse structure override the loop.
  virtual Operator dg_matrix(const G& group, const Element& y) const {
    return operator_from_columns(group, [&](const Vector& u) -> Vector { return dg(y, u); });
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
// y = [[R, 0], [0, [[I, w], [0, 1]]]] of SO3xR3Group (so3xr3_state.hpp): y' = y g(y) with
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
    const Eigen::Vector3d w = so3xr3::omega(y);
    return so3xr3::embed<M>(w, acceleration(so3xr3::rotation(y), w));
  }
  // Along y' = y dir, dir = hat(u_r, u_w): R' = R hat(u_r), w' = u_w, so (R^T gamma)' = -hat(u_r) R^T gamma
  // = (R^T gamma) x u_r, and a' = J^-1 ((J u_w) x w + (J w) x u_w + m chi x ((R^T gamma) x u_r)).
  template <class M>
  M dg(const M& y, const M& dir, const M&) const {
    const Eigen::Vector3d w = so3xr3::omega(y), u_r = so3::vee(so3xr3::rotation(dir)), u_w = so3xr3::omega(dir);
    const Eigen::Vector3d b = so3xr3::rotation(y).transpose() * params.gravity;
    const Eigen::Vector3d da = (inertia * u_w).cross(w) + (inertia * w).cross(u_w) +
                               params.mass * params.center.cross(b.cross(u_r));
    return so3xr3::embed<M>(u_w, inverse * da);
  }
  // The same on the coordinates (u_r, u_w): [[0, I], [J^-1 m hat(chi) hat(b), J^-1 (hat(J w) - hat(w) J)]].
  SO3xR3Group::Operator dg_matrix(const SO3xR3Group&, const SO3xR3Group::Element& y) const {
    const Eigen::Vector3d w = so3xr3::omega(y), b = so3xr3::rotation(y).transpose() * params.gravity;
    SO3xR3Group::Operator m = SO3xR3Group::Operator::Zero();
    m.topRightCorner<3, 3>().setIdentity();
    m.bottomLeftCorner<3, 3>() = inverse * (params.mass * so3::hat(params.center) * so3::hat(b));
    m.bottomRightCorner<3, 3>() = inverse * (so3::hat(inertia * w) - so3::hat(w) * inertia);
    return m;
  }
  template <class M>
  double energy(const M& y) const {
    const Eigen::Vector3d w = so3xr3::omega(y);
    return 0.5 * w.dot(inertia * w) - params.mass * params.gravity.dot(so3xr3::rotation(y) * params.center);
  }
  template <class M>
  double vertical_momentum(const M& y) const {
    return (so3xr3::rotation(y) * (inertia * so3xr3::omega(y))).z();
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
    const Eigen::Vector3d w = so3xr3::omega(y);
    return 0.5 * w.dot(inertia * w) + params.mass * params.gravity.norm() * params.center.norm();
  }
  template <class M>
  double momentum_scale(const M& y) const { return (inertia * so3xr3::omega(y)).norm(); }
  // y(0): the state of (R(0), w(0)).
  Eigen::MatrixXd start() const { return so3xr3::state(params.rotation, params.omega); }

 private:
  Eigen::Vector3d acceleration(const Eigen::Matrix3d& r, const Eigen::Vector3d& w) const {
    const Eigen::Vector3d torque = params.mass * params.center.cross(r.transpose() * params.gravity);
    return inverse * ((inertia * w).cross(w) + torque);
  }
};

// The stiff rigid body on SO(3) x R^3 (stiff_body_params.hpp) in the heavy top's state layout: y' = y g(t, y) with
//   g(t, y) = [[hat(w), 0], [0, [[0, a], [0, 0]]]],  a = J^-1 ((J w) x w - k vee(skew R) - c w + f(t)).
// Forced and damped, it conserves nothing. f(t) is added to g alone, so dg does not depend on t.
struct StiffBody {
  StiffBodyParams params;
  double time = 0.0;  // the t of f(t): the integrators' stage time (VectorFieldOf::set_time), 0 in solves

  explicit StiffBody(const StiffBodyParams& p) : params(p) {}

  void set_time(double t) { time = t; }
  template <class M>
  M g(const M& y) const {
    const Eigen::Vector3d w = so3xr3::omega(y), r = spring(so3xr3::rotation(y));
    const Eigen::Vector3d torque = momentum(w).cross(w) - params.k * r - damping(params) * w + forcing();
    return so3xr3::embed<M>(w, torque.cwiseQuotient(params.J));
  }
  // Along y' = y dir, dir = hat(u_r, u_w): R' = R hat(u_r), w' = u_w, and vee(skew(R hat(u))) = P u with
  // P = (tr(R) I - R^T) / 2, so a' = J^-1 ((J u_w) x w + (J w) x u_w - k P u_r - c u_w).
  template <class M>
  M dg(const M& y, const M& dir, const M&) const {
    const Eigen::Vector3d w = so3xr3::omega(y), u_r = so3::vee(so3xr3::rotation(dir)), u_w = so3xr3::omega(dir);
    const Eigen::Vector3d da = momentum(u_w).cross(w) + momentum(w).cross(u_w) -
                               params.k * (spring_slope(so3xr3::rotation(y)) * u_r) - damping(params) * u_w;
    return so3xr3::embed<M>(u_w, da.cwiseQuotient(params.J));
  }
  // The same on the coordinates (u_r, u_w): [[0, I], [-J^-1 k P, J^-1 (hat(J w) - hat(w) J - c I)]].
  SO3xR3Group::Operator dg_matrix(const SO3xR3Group&, const SO3xR3Group::Element& y) const {
    const Eigen::Vector3d w = so3xr3::omega(y);
    const Eigen::Matrix3d inertia = params.J.asDiagonal();
    const Eigen::Vector3d inverse = params.J.cwiseInverse();
    SO3xR3Group::Operator m = SO3xR3Group::Operator::Zero();
    m.topRightCorner<3, 3>().setIdentity();
    m.bottomLeftCorner<3, 3>() = inverse.asDiagonal() * (-params.k * spring_slope(so3xr3::rotation(y)));
    m.bottomRightCorner<3, 3>() = inverse.asDiagonal() * (so3::hat(inertia * w) - so3::hat(w) * inertia -
                                                          damping(params) * Eigen::Matrix3d::Identity());
    return m;
  }
  // y(0): the state of (R(0), w(0)).
  Eigen::MatrixXd start() const { return so3xr3::state(params.rotation, params.omega); }

 private:
  Eigen::Vector3d momentum(const Eigen::Vector3d& w) const { return params.J.cwiseProduct(w); }
  // vee(skew R): the spring's twist away from the identity (sin of the angle about R's axis).
  static Eigen::Vector3d spring(const Eigen::Matrix3d& r) { return so3::vee(0.5 * (r - r.transpose())); }
  static Eigen::Matrix3d spring_slope(const Eigen::Matrix3d& r) {
    return 0.5 * (r.trace() * Eigen::Matrix3d::Identity() - r.transpose());
  }
  Eigen::Vector3d forcing() const {
    return params.f.cwiseProduct(Eigen::Vector3d(std::sin(2.0 * time), std::cos(time), 1.0));
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
  // A time-dependent problem (one with set_time) sees the stage time; the autonomous ones have nothing to set.
  void set_time(double t) override {
    if constexpr (requires { problem_.set_time(t); }) problem_.set_time(t);
  }
  const Problem& problem() const { return problem_; }

 private:
  G group_;
  Problem problem_;
};

// The groups each problem is defined on (validate() checks before make_field). The paper's problems are matrix
// formulas with skew values: defined on every group of n x n matrices whose algebra holds the skew matrices
// (hat(vee(S)) = S for a skew S). rigid-body's formulas are 3 x 3 rotations': SO(3) alone; heavy-top's and
// stiff-body's the 7 x 7 states of SO(3) x R^3; chain's the strips of (SE(3) x R^6)^k (chain.hpp).
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
// The problems written on SO(3) x R^3 (so3xr3_state.hpp): their parameters give their start (R(0), w(0)), never z.
inline bool on_so3xr3(ProblemKind kind) {
  return kind == ProblemKind::heavy_top || kind == ProblemKind::stiff_body;
}
// The problems whose parameters give their start, never z: the two on SO(3) x R^3 and the chain.
inline bool starts_from_parameters(ProblemKind kind) { return on_so3xr3(kind) || kind == ProblemKind::chain; }
template <class G>
bool defined_on(ProblemKind kind, const G& group) {
  if (kind == ProblemKind::rigid_body) return std::is_same_v<G, SO3Group>;
  if (on_so3xr3(kind)) return std::is_same_v<G, SO3xR3Group>;
  if (kind == ProblemKind::chain) return std::is_same_v<G, SE3xR6PowerGroup>;
  return algebra_holds_skew_matrices(group);
}
// The one n a problem is written for, if any: rigid-body's, heavy-top's and stiff-body's 3 (their group's index).
inline std::optional<int> required_index(ProblemKind kind) {
  if (kind == ProblemKind::rigid_body || on_so3xr3(kind)) return 3;
  return std::nullopt;
}
// The one group family a problem is written for, if any: heavy-top's and stiff-body's SO(3) x R^3, chain's
// (SE(3) x R^6)^k (any n = k the family takes).
inline std::optional<std::string> required_group(ProblemKind kind) {
  if (on_so3xr3(kind)) return SOxRFamily::kName;
  if (kind == ProblemKind::chain) return SExRPowerFamily::kName;
  return std::nullopt;
}

// The field of a request's problem on group G (one it is defined_on; validate() checks).
template <class G>
std::unique_ptr<VectorField<G>> make_field(const G& group, ProblemKind kind, const RigidBodyParams& rb,
                                           const HeavyTopParams& top = {}, const StiffBodyParams& stiff = {},
                                           const ChainParams& chain = {}) {
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
    case ProblemKind::stiff_body:
      if constexpr (std::is_same_v<G, SO3xR3Group>)
        return std::make_unique<VectorFieldOf<G, StiffBody>>(group, StiffBody{stiff});
      break;
    case ProblemKind::chain:
      if constexpr (std::is_same_v<G, SE3xR6PowerGroup>)
        return std::make_unique<VectorFieldOf<G, Chain>>(group, Chain{chain});
      break;
  }
  return nullptr;
}

}  // namespace lienewton
