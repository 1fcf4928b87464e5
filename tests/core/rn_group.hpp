#pragma once
// The abelian group R^n under addition: exp and log are the identity, ad = 0, dexp = dexpinv = Id. Both Newton
// versions must reduce to classical Newton on it; no production path uses it.
#include <Eigen/Dense>
#include <cstdint>
#include <limits>
#include <random>
#include <string>

#include "core/groups/lie_group.hpp"

namespace lienewton {

struct RnGroup {
  using Element = Eigen::VectorXd;
  using Vector = Eigen::VectorXd;
  using Operator = Eigen::MatrixXd;
  using Spectral = Eigen::VectorXd;
  static constexpr double kLogRadius = std::numeric_limits<double>::infinity();  // log is global
  static constexpr double kLogMargin = 0.0;
  static constexpr const char* kAngleName = "angle";  // always 0: nothing wraps
  static constexpr const char* kLogBoundaryName = "infinity";
  static constexpr const char* kAlgebraDimension = "n";

  explicit RnGroup(int n) : n_(n) {}
  int n() const { return n_; }
  std::string name() const { return "R^" + std::to_string(n_); }
  int dim() const { return n_; }
  Element identity() const { return Element::Zero(n_); }
  Element compose(const Element& a, const Element& b) const { return a + b; }
  Element inverse(const Element& a) const { return -a; }
  Element hat(const Vector& v) const { return v; }
  Vector vee(const Element& m) const { return m; }
  Vector bracket(const Vector&, const Vector&) const { return Vector::Zero(n_); }
  Operator ad_matrix(const Vector&) const { return Operator::Zero(n_, n_); }

  Element exp(const Vector& v) const { return v; }
  Element times_exp(const Element& y, const Vector& v) const { return y + v; }
  Spectral spectral(const Vector& v) const { return v; }
  Spectral log(const Element& r) const { return r; }
  Vector log_vector(const Element& r, double& angle) const {
    angle = 0.0;
    return r;
  }
  Vector vector(const Spectral& s) const { return s; }
  double angle(const Spectral&) const { return 0.0; }
  Vector dexp(const Spectral&, const Vector& u) const { return u; }
  Vector dexpinv(const Spectral&, const Vector& u) const { return u; }
  Operator dexp_matrix(const Spectral&) const { return Operator::Identity(n_, n_); }
  Operator dexpinv_matrix(const Spectral&) const { return Operator::Identity(n_, n_); }

  double defect(const Element&) const { return 0.0; }
  Element project(const Element& y) const { return y; }
  double principal_angle(double theta) const { return theta; }
  Element tangent(const Element&, const Element& u) const { return u; }  // y + t u

  // A request's matrix is a column of n entries; every finite one is an element, reachable from any other.
  Element element(const Eigen::MatrixXd& m) const { return m.col(0); }
  Eigen::MatrixXd matrix(const Element& y) const { return y; }
  Element random(std::uint64_t seed) const {
    std::mt19937_64 rng(seed);
    Element y(n_);
    for (int i = 0; i < n_; ++i) y(i) = static_cast<double>(rng() >> 11) * 0x1.0p-53;
    return y;
  }
  std::string not_an_element(const Eigen::MatrixXd&, const std::string&) const { return {}; }
  std::string not_reachable(const Eigen::MatrixXd&, const Eigen::MatrixXd&) const { return {}; }
  Element component_identity(const Element&) const { return identity(); }

 private:
  int n_;
};
static_assert(LieGroup<RnGroup>);

}  // namespace lienewton

#include "core/solvers/run_method.hpp"

// The solvers on R^n are compiled once, in rn_instances.cpp, for the tests that solve on it.
namespace lienewton {
LIENEWTON_SOLVERS_ON(extern, RnGroup)
}  // namespace lienewton
