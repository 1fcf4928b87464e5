#pragma once
// What the solvers and the requests need of a Lie group G, as a concept every group static_asserts:
//   Element (group element), Vector (algebra coordinates on a basis of dimension dim()), Operator (dim x dim
//   matrix on coordinates), Spectral (what exp/log computed that dexp/dexpinv can reuse: the decomposition of
//   z^-1 y serves both log and dexpinv);
//   the group law (identity, compose, inverse), the algebra (hat, vee, bracket, ad_matrix),
//   exp and times_exp(y, v) = y exp(v) (formed so that long products stay on the group),
//   log through Spectral (log throws LogDomainError outside its domain) or straight to coordinates
//   (log_vector: cheaper when no differential follows), dexp (2.10) and dexpinv (3.9) through Spectral,
//   and what the group owns about its log: kLogRadius (log is defined for angle(...) < kLogRadius),
//   kLogMargin (how close to the radius log still answers), defect(y), the distance of y from the group
//   (||y^T y - I||_F on SO(N)), and project(y), the group element nearest to y (the orthogonal polar factor);
//   tangent(y, U) = d/dt y exp(tU) at t = 0, as an Element-shaped matrix (y U on a matrix group), which the
//   problems' differentials take; principal_angle(theta), the angle of exp(v) from the angle theta of v
//   (wrapped into [0, kLogRadius] on SO(N)),
//   and the words a reason uses for them: kAngleName ("rotation angle"), kLogBoundaryName ("pi");
// and what the requests need of it: element(m) and matrix(y) convert between a request's matrix (rows) and an
// Element; random(seed), the seeded start; not_an_element(m, name) and not_reachable(y0, z), why a request's
// z or y0 is refused (empty: accepted), in the group's words; kAlgebraDimension, dim() as a formula in n.
// Optionally rotation(y), the 3 x 3 rotation part of an element (SO(3), SE(3) and products with them first), which
// pictures of frames draw; a group without it is refused there.
// Adding a group: see docs/architecture.md ("Where a change goes").
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace lienewton {

template <class G>
concept LieGroup = requires(const G g, const typename G::Element y, const typename G::Vector v,
                            const typename G::Spectral s, double& angle, const Eigen::MatrixXd m,
                            const std::string name, std::uint64_t seed) {
  { g.n() } -> std::same_as<int>;
  { g.name() } -> std::convertible_to<std::string>;  // as a title says it: "SO(3)"
  { g.dim() } -> std::same_as<int>;
  { g.identity() } -> std::convertible_to<typename G::Element>;
  { g.compose(y, y) } -> std::convertible_to<typename G::Element>;
  { g.inverse(y) } -> std::convertible_to<typename G::Element>;
  { g.hat(v) } -> std::convertible_to<typename G::Element>;
  { g.vee(y) } -> std::convertible_to<typename G::Vector>;
  { g.bracket(v, v) } -> std::convertible_to<typename G::Vector>;
  { g.ad_matrix(v) } -> std::convertible_to<typename G::Operator>;
  { g.exp(v) } -> std::convertible_to<typename G::Element>;
  { g.times_exp(y, v) } -> std::convertible_to<typename G::Element>;
  { g.spectral(v) } -> std::convertible_to<typename G::Spectral>;
  { g.log(y) } -> std::convertible_to<typename G::Spectral>;
  { g.log_vector(y, angle) } -> std::convertible_to<typename G::Vector>;
  { g.vector(s) } -> std::convertible_to<typename G::Vector>;
  { g.angle(s) } -> std::same_as<double>;
  { g.dexp(s, v) } -> std::convertible_to<typename G::Vector>;
  { g.dexpinv(s, v) } -> std::convertible_to<typename G::Vector>;
  { g.dexp_matrix(s) } -> std::convertible_to<typename G::Operator>;
  { g.dexpinv_matrix(s) } -> std::convertible_to<typename G::Operator>;
  { g.defect(y) } -> std::same_as<double>;
  { g.project(y) } -> std::convertible_to<typename G::Element>;
  { g.principal_angle(angle) } -> std::same_as<double>;
  { g.tangent(y, y) } -> std::convertible_to<typename G::Element>;
  { G::kLogRadius } -> std::convertible_to<double>;
  { G::kLogMargin } -> std::convertible_to<double>;
  { G::kAngleName } -> std::convertible_to<std::string>;
  { G::kLogBoundaryName } -> std::convertible_to<std::string>;
  { G::kAlgebraDimension } -> std::convertible_to<std::string>;
  { g.element(m) } -> std::convertible_to<typename G::Element>;
  { g.matrix(y) } -> std::same_as<Eigen::MatrixXd>;
  { g.random(seed) } -> std::convertible_to<typename G::Element>;
  { g.not_an_element(m, name) } -> std::same_as<std::string>;
  { g.not_reachable(m, m) } -> std::same_as<std::string>;
};

// Whether G's operators are sparse matrices (a system of bodies): the Newton matrix is then factored sparse.
template <class G>
inline constexpr bool kSparseOperator =
    std::is_base_of_v<Eigen::SparseMatrixBase<typename G::Operator>, typename G::Operator>;

// G's operators at run-time size, for matrices built from them (stage systems): a sparse one stays sparse.
template <class G>
using DynamicOperator = std::conditional_t<kSparseOperator<G>, Eigen::SparseMatrix<double>, Eigen::MatrixXd>;

// Coordinates and operators sized by the group (fixed-size types ignore the size arguments).
template <class G>
typename G::Vector zero_vector(const G& g) {
  return G::Vector::Zero(g.dim());
}
template <class G>
typename G::Vector basis_vector(const G& g, int i) {
  return G::Vector::Unit(g.dim(), i);
}
// A sparse Operator (PowerGroup's) is the empty pattern, or the identity's diagonal.
template <class G>
typename G::Operator zero_operator(const G& g) {
  if constexpr (kSparseOperator<G>) {
    return typename G::Operator(g.dim(), g.dim());
  } else {
    return G::Operator::Zero(g.dim(), g.dim());
  }
}
template <class G>
typename G::Operator identity_operator(const G& g) {
  if constexpr (kSparseOperator<G>) {
    typename G::Operator m(g.dim(), g.dim());
    m.setIdentity();
    return m;
  } else {
    return G::Operator::Identity(g.dim(), g.dim());
  }
}

// An operator set column by column, in order i = 0, 1, ..., by a caller that produces its columns in passes (a
// user's dg_y formed a few directions at a time): a sparse operator keeps the columns' nonzeros only.
template <class G>
class OperatorColumns {
 public:
  explicit OperatorColumns(const G& g) : dim_(g.dim()) {
    if constexpr (!kSparseOperator<G>) m_ = zero_operator(g);
  }
  void set(int i, const typename G::Vector& c) {
    if constexpr (kSparseOperator<G>) {
      for (Eigen::Index r = 0; r < c.size(); ++r)
        if (c[r] != 0.0) entries_.emplace_back(static_cast<int>(r), i, c[r]);
    } else {
      m_.col(i) = c;
    }
  }
  typename G::Operator take() {
    if constexpr (kSparseOperator<G>) {
      m_.resize(dim_, dim_);
      m_.setFromTriplets(entries_.begin(), entries_.end());
      entries_ = {};
    }
    return std::move(m_);
  }

 private:
  int dim_;
  typename G::Operator m_;
  std::vector<Eigen::Triplet<double>> entries_;  // a sparse operator's nonzeros until take()
};

// The operator whose column i is column(e_i), for differentials known only by their action (difference quotients,
// a user's df, the default dg_matrix).
template <class G, class Column>
typename G::Operator operator_from_columns(const G& g, Column column) {
  OperatorColumns<G> columns(g);
  for (int i = 0; i < g.dim(); ++i) columns.set(i, column(basis_vector(g, i)));
  return columns.take();
}

// Every stored entry finite (a sparse operator's pattern only: its implicit zeros are).
template <class Op>
bool operator_all_finite(const Op& m) {
  if constexpr (std::is_base_of_v<Eigen::SparseMatrixBase<Op>, Op>) {
    for (Eigen::Index c = 0; c < m.outerSize(); ++c)
      for (typename Op::InnerIterator it(m, c); it; ++it)
        if (!std::isfinite(it.value())) return false;
    return true;
  } else {
    return m.allFinite();
  }
}

// log answers at this angle (the largest rotation angle of an element, or of a Spectral).
template <class G>
bool inside_log_domain(double angle) {
  return angle <= G::kLogRadius - G::kLogMargin;
}
// How far a point at this angle is from the boundary of log's domain (pi - angle on SO(N)).
template <class G>
double log_boundary_distance(double angle) {
  return G::kLogRadius - angle;
}

}  // namespace lienewton
