#pragma once
// The abelian groups R^n (Element a vector) and R^(n x n) (Element an n x n matrix) under addition: exp and log
// are the identity (coordinates: the entries, column by column), ad = 0, dexp = dexpinv = Id, and the tangent at
// y in direction U is U. Both Newton versions must reduce to classical Newton on them; no production path uses
// them. R^(n x n) is also registered as a group the requests can name (matrix_sum_group.hpp).
#include <Eigen/Dense>
#include <cstdint>
#include <limits>
#include <random>
#include <string>

#include "core/groups/lie_group.hpp"

namespace lienewton {

template <class E>
struct AdditiveGroup {
  using Element = E;
  using Vector = Eigen::VectorXd;
  using Operator = Eigen::MatrixXd;
  using Spectral = Eigen::VectorXd;
  static constexpr bool kVectors = Element::ColsAtCompileTime == 1;
  static constexpr double kLogRadius = std::numeric_limits<double>::infinity();  // log is global
  static constexpr double kLogMargin = 0.0;
  static constexpr const char* kAngleName = "angle";  // always 0: nothing wraps
  static constexpr const char* kLogBoundaryName = "infinity";
  static constexpr const char* kAlgebraDimension = kVectors ? "n" : "n^2";

  explicit AdditiveGroup(int n) : n_(n), cols_(kVectors ? 1 : n) {}
  int n() const { return n_; }
  std::string name() const {
    const std::string n = std::to_string(n_);
    return kVectors ? "R^" + n : "R^(" + n + "x" + n + ")";
  }
  int dim() const { return n_ * cols_; }
  Element identity() const { return Element::Zero(n_, cols_); }
  Element compose(const Element& a, const Element& b) const { return a + b; }
  Element inverse(const Element& a) const { return -a; }
  Element hat(const Vector& v) const { return Eigen::Map<const Element>(v.data(), n_, cols_); }
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

  // A request's matrix holds the entries (n x 1 for R^n); every finite one is an element, reachable from any
  // other. The seeded element has entries in [0, 1), drawn column by column.
  Element element(const Eigen::MatrixXd& m) const { return Element(m); }
  Eigen::MatrixXd matrix(const Element& y) const { return y; }
  Element random(std::uint64_t seed) const {
    std::mt19937_64 rng(seed);
    Element y(n_, cols_);
    for (int j = 0; j < cols_; ++j)
      for (int i = 0; i < n_; ++i) y(i, j) = static_cast<double>(rng() >> 11) * 0x1.0p-53;
    return y;
  }
  std::string not_an_element(const Eigen::MatrixXd&, const std::string&) const { return {}; }
  std::string not_reachable(const Eigen::MatrixXd&, const Eigen::MatrixXd&) const { return {}; }

 private:
  int n_, cols_;
};

using RnGroup = AdditiveGroup<Eigen::VectorXd>;
static_assert(LieGroup<RnGroup>);

}  // namespace lienewton

#include "core/solvers/run_method.hpp"

// The solvers on R^n are compiled once, in rn_instances.cpp, for the tests that solve on it.
namespace lienewton {
LIENEWTON_SOLVERS_ON(extern, RnGroup)
}  // namespace lienewton
