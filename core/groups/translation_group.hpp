#pragma once
// R^k under addition, as the matrices [[I, x], [0, 1]] ((k+1) x (k+1)): the translations, so that R^k is a matrix
// group whose product is the matrix product (x + y exactly: the 1s and 0s add nothing) and its elements sit in a
// block-diagonal product (product_group.hpp) beside any other matrix group. Coordinates are x itself: exp and log
// are the identity on them, ad = 0, dexp = dexpinv = Id; log is global (kLogRadius infinite).
#include <Eigen/Dense>
#include <cstdint>
#include <limits>
#include <random>
#include <string>

#include "lie_group.hpp"

namespace lienewton {

template <int K>
struct TranslationGroup {
  using Element = Eigen::Matrix<double, K + 1, K + 1>;
  using Vector = Eigen::Matrix<double, K, 1>;
  using Operator = Eigen::Matrix<double, K, K>;
  using Spectral = Vector;
  static constexpr double kLogRadius = std::numeric_limits<double>::infinity();
  static constexpr double kLogMargin = 0.0;
  static constexpr const char* kAngleName = "angle";  // always 0: nothing wraps
  static constexpr const char* kLogBoundaryName = "infinity";
  static constexpr const char* kAlgebraDimension = "k";

  int n() const { return K; }
  std::string name() const { return "R^" + std::to_string(K); }
  int dim() const { return K; }
  Element identity() const { return Element::Identity(); }
  Element compose(const Element& a, const Element& b) const { return a * b; }
  Element inverse(const Element& a) const { return exp(-translation(a)); }
  Element hat(const Vector& v) const {
    Element m = Element::Zero();
    m.template topRightCorner<K, 1>() = v;
    return m;
  }
  Vector vee(const Element& m) const { return translation(m); }
  Vector bracket(const Vector&, const Vector&) const { return Vector::Zero(); }
  Operator ad_matrix(const Vector&) const { return Operator::Zero(); }

  Element exp(const Vector& v) const { return identity() + hat(v); }
  Element times_exp(const Element& y, const Vector& v) const { return y + hat(v); }  // y hat(v) = hat(v)
  Spectral spectral(const Vector& v) const { return v; }
  Spectral log(const Element& y) const { return translation(y); }
  Vector log_vector(const Element& y, double& angle) const {
    angle = 0.0;
    return translation(y);
  }
  Vector vector(const Spectral& s) const { return s; }
  double angle(const Spectral&) const { return 0.0; }
  Vector dexp(const Spectral&, const Vector& u) const { return u; }
  Vector dexpinv(const Spectral&, const Vector& u) const { return u; }
  Operator dexp_matrix(const Spectral&) const { return Operator::Identity(); }
  Operator dexpinv_matrix(const Spectral&) const { return Operator::Identity(); }

  // How far y is from [[I, x], [0, 1]]: every entry but x's.
  double defect(const Element& y) const { return (y - exp(translation(y))).norm(); }
  Element project(const Element& y) const { return exp(translation(y)); }
  double principal_angle(double theta) const { return theta; }
  Element tangent(const Element& y, const Element& u) const { return y * u; }  // = u on the algebra

  Element element(const Eigen::MatrixXd& m) const { return Element(m); }
  Eigen::MatrixXd matrix(const Element& y) const { return Eigen::MatrixXd(y); }
  // x with entries in [0, 1), drawn in order.
  Element random(std::uint64_t seed) const {
    std::mt19937_64 rng(seed);
    Vector x;
    for (int i = 0; i < K; ++i) x(i) = static_cast<double>(rng() >> 11) * 0x1.0p-53;
    return exp(x);
  }
  std::string not_an_element(const Eigen::MatrixXd& m, const std::string& name) const {
    if (m == matrix(exp(translation(Element(m))))) return {};
    return name + " must be [[I, x], [0, 1]] (an element of R^" + std::to_string(K) +
           " as a matrix): only its last column may differ from the identity's";
  }
  std::string not_reachable(const Eigen::MatrixXd&, const Eigen::MatrixXd&) const { return {}; }

 private:
  static Vector translation(const Element& y) { return y.template topRightCorner<K, 1>(); }
};

}  // namespace lienewton
