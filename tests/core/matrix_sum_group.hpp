#pragma once
// The abelian group of real n x n matrices under addition, registered as "Rnxn" the way a real group is: this
// header and its one registry line below are all it takes for every request (solve, sweep, basins, integrate,
// work-precision) to run on it. exp and log are the identity (coordinates: the entries, column by column), ad = 0,
// dexp = dexpinv = Id and the tangent at y in direction U is U, so both Newton versions are classical Newton on
// f(y) = y - z - h g(y); its algebra
// holds the skew matrices, so the paper's two problems are defined on it. No production path names it.
#include <Eigen/Dense>
#include <cstdint>
#include <limits>
#include <random>
#include <string>

#include "core/groups/lie_group.hpp"
#include "core/register_group.hpp"

namespace lienewton {

struct MatrixSumGroup {
  using Element = Eigen::MatrixXd;
  using Vector = Eigen::VectorXd;
  using Operator = Eigen::MatrixXd;
  using Spectral = Eigen::VectorXd;
  static constexpr double kLogRadius = std::numeric_limits<double>::infinity();  // log is global
  static constexpr double kLogMargin = 0.0;
  static constexpr const char* kAngleName = "angle";  // always 0: nothing wraps
  static constexpr const char* kLogBoundaryName = "infinity";
  static constexpr const char* kAlgebraDimension = "n^2";

  explicit MatrixSumGroup(int n) : n_(n) {}
  int n() const { return n_; }
  std::string name() const { return "R^(" + std::to_string(n_) + "x" + std::to_string(n_) + ")"; }
  int dim() const { return n_ * n_; }
  Element identity() const { return Element::Zero(n_, n_); }
  Element compose(const Element& a, const Element& b) const { return a + b; }
  Element inverse(const Element& a) const { return -a; }
  Element hat(const Vector& v) const { return Eigen::Map<const Element>(v.data(), n_, n_); }
  Vector vee(const Element& m) const { return Eigen::Map<const Vector>(m.data(), dim()); }
  Vector bracket(const Vector&, const Vector&) const { return Vector::Zero(dim()); }
  Operator ad_matrix(const Vector&) const { return Operator::Zero(dim(), dim()); }

  Element exp(const Vector& v) const { return hat(v); }
  Element times_exp(const Element& y, const Vector& v) const { return y + hat(v); }
  Spectral spectral(const Vector& v) const { return v; }
  Spectral log(const Element& r) const { return vee(r); }
  Vector log_vector(const Element& r, double& angle) const {
    angle = 0.0;
    return vee(r);
  }
  Vector vector(const Spectral& s) const { return s; }
  double angle(const Spectral&) const { return 0.0; }
  Vector dexp(const Spectral&, const Vector& u) const { return u; }
  Vector dexpinv(const Spectral&, const Vector& u) const { return u; }
  Operator dexp_matrix(const Spectral&) const { return Operator::Identity(dim(), dim()); }
  Operator dexpinv_matrix(const Spectral&) const { return Operator::Identity(dim(), dim()); }

  double defect(const Element&) const { return 0.0; }
  Element project(const Element& y) const { return y; }
  double principal_angle(double theta) const { return theta; }
  Element tangent(const Element&, const Element& u) const { return u; }  // y + t U

  // Every finite n x n matrix is an element, reachable from any other; the seeded start has entries in [0, 1).
  Element element(const Eigen::MatrixXd& m) const { return m; }
  Eigen::MatrixXd matrix(const Element& y) const { return y; }
  Element random(std::uint64_t seed) const {
    std::mt19937_64 rng(seed);
    Element y(n_, n_);
    for (int j = 0; j < n_; ++j)
      for (int i = 0; i < n_; ++i) y(i, j) = static_cast<double>(rng() >> 11) * 0x1.0p-53;
    return y;
  }
  std::string not_an_element(const Eigen::MatrixXd&, const std::string&) const { return {}; }
  std::string not_reachable(const Eigen::MatrixXd&, const Eigen::MatrixXd&) const { return {}; }
  Element component_identity(const Element&) const { return identity(); }

 private:
  int n_;
};
static_assert(LieGroup<MatrixSumGroup>);

struct MatrixSumFamily {
  static constexpr const char* kName = "Rnxn";
  template <class F>
  static decltype(auto) with_group(int n, F&& f) {
    return f(MatrixSumGroup(n));
  }
};

// The solvers on it are compiled once, in matrix_sum_instances.cpp.
LIENEWTON_SOLVERS_ON(extern, MatrixSumGroup)

inline const bool kMatrixSumRegistered = register_group<MatrixSumFamily>();

}  // namespace lienewton
