#pragma once
// The direct product G1 x G2 of two matrix groups (manif's Bundle), as block-diagonal matrices [[y1, 0], [0, y2]]:
// the product is the matrix product, and everything else comes from the factors block by block: coordinates
// (v1, v2), hat/vee, bracket and ad (block-diagonal), exp, log (a Spectral per factor), dexp (2.10) and dexpinv
// (3.9) and their matrices (block-diagonal, so the Newton system is the factors' side by side), defect and
// projection, tangent, membership. One factor has a global log (R^k, translation_group.hpp): the other's log
// domain is the product's, with its angle, boundary and words (SO(3) x R^3: rotation angle, pi).
#include <Eigen/Dense>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "lie_group.hpp"

namespace lienewton {

template <LieGroup G1, LieGroup G2>
struct ProductGroup {
  static constexpr int kRows1 = G1::Element::RowsAtCompileTime, kRows2 = G2::Element::RowsAtCompileTime;
  static constexpr int kDim1 = G1::Vector::RowsAtCompileTime, kDim2 = G2::Vector::RowsAtCompileTime;
  static_assert(kRows1 > 0 && kRows2 > 0 && kDim1 > 0 && kDim2 > 0, "the factors are fixed-size groups");
  static_assert(G2::kLogRadius == std::numeric_limits<double>::infinity() &&
                    G1::kLogRadius < std::numeric_limits<double>::infinity(),
                "the second factor has the global log (R^k), the first the product's log domain");

  using Element = Eigen::Matrix<double, kRows1 + kRows2, kRows1 + kRows2>;
  using Vector = Eigen::Matrix<double, kDim1 + kDim2, 1>;
  using Operator = Eigen::Matrix<double, kDim1 + kDim2, kDim1 + kDim2>;
  struct Spectral {
    typename G1::Spectral first;
    typename G2::Spectral second;
  };
  static constexpr double kLogRadius = G1::kLogRadius;
  static constexpr double kLogMargin = G1::kLogMargin;
  static constexpr const char* kAngleName = G1::kAngleName;
  static constexpr const char* kLogBoundaryName = G1::kLogBoundaryName;
  static inline const std::string kAlgebraDimension = std::to_string(kDim1 + kDim2);

  int n() const { return g1_.n(); }
  std::string name() const { return g1_.name() + "x" + g2_.name(); }
  int dim() const { return kDim1 + kDim2; }
  Element identity() const { return Element::Identity(); }
  Element compose(const Element& a, const Element& b) const { return join(g1_.compose(first(a), first(b)),
                                                                          g2_.compose(second(a), second(b))); }
  Element inverse(const Element& a) const { return join(g1_.inverse(first(a)), g2_.inverse(second(a))); }
  Element hat(const Vector& v) const { return join(g1_.hat(head(v)), g2_.hat(tail(v))); }
  Vector vee(const Element& m) const { return stack(g1_.vee(first(m)), g2_.vee(second(m))); }
  Vector bracket(const Vector& a, const Vector& b) const {
    return stack(g1_.bracket(head(a), head(b)), g2_.bracket(tail(a), tail(b)));
  }
  Operator ad_matrix(const Vector& v) const { return diagonal(g1_.ad_matrix(head(v)), g2_.ad_matrix(tail(v))); }

  Element exp(const Vector& v) const { return join(g1_.exp(head(v)), g2_.exp(tail(v))); }
  Element times_exp(const Element& y, const Vector& v) const {
    return join(g1_.times_exp(first(y), head(v)), g2_.times_exp(second(y), tail(v)));
  }
  Spectral spectral(const Vector& v) const { return {g1_.spectral(head(v)), g2_.spectral(tail(v))}; }
  Spectral log(const Element& y) const { return {g1_.log(first(y)), g2_.log(second(y))}; }
  Vector log_vector(const Element& y, double& angle) const {
    double ignored = 0.0;
    return stack(g1_.log_vector(first(y), angle), g2_.log_vector(second(y), ignored));
  }
  Vector vector(const Spectral& s) const { return stack(g1_.vector(s.first), g2_.vector(s.second)); }
  double angle(const Spectral& s) const { return g1_.angle(s.first); }
  Vector dexp(const Spectral& s, const Vector& u) const {
    return stack(g1_.dexp(s.first, head(u)), g2_.dexp(s.second, tail(u)));
  }
  Vector dexpinv(const Spectral& s, const Vector& u) const {
    return stack(g1_.dexpinv(s.first, head(u)), g2_.dexpinv(s.second, tail(u)));
  }
  Operator dexp_matrix(const Spectral& s) const {
    return diagonal(g1_.dexp_matrix(s.first), g2_.dexp_matrix(s.second));
  }
  Operator dexpinv_matrix(const Spectral& s) const {
    return diagonal(g1_.dexpinv_matrix(s.first), g2_.dexpinv_matrix(s.second));
  }

  // The factors' defects and the off-diagonal blocks' size, together.
  double defect(const Element& y) const {
    const double off = std::hypot(y.template topRightCorner<kRows1, kRows2>().norm(),
                                  y.template bottomLeftCorner<kRows2, kRows1>().norm());
    return std::hypot(std::hypot(g1_.defect(first(y)), g2_.defect(second(y))), off);
  }
  Element project(const Element& y) const { return join(g1_.project(first(y)), g2_.project(second(y))); }
  // The rotation of the first factor, where it has one (SO(3) x R^3: R; SE(3) x R^6: T's R).
  Eigen::Matrix3d rotation(const Element& y) const
    requires requires(const G1& g, const typename G1::Element& e) { g.rotation(e); }
  {
    return g1_.rotation(first(y));
  }
  double principal_angle(double theta) const { return g1_.principal_angle(theta); }
  Element tangent(const Element& y, const Element& u) const {
    return join(g1_.tangent(first(y), first(u)), g2_.tangent(second(y), second(u)));
  }

  Element element(const Eigen::MatrixXd& m) const { return Element(m); }
  Eigen::MatrixXd matrix(const Element& y) const { return Eigen::MatrixXd(y); }
  Element random(std::uint64_t seed) const { return join(g1_.random(seed), g2_.random(seed)); }
  // Block diagonal exactly, each block its factor's element (in the factor's words, naming the block).
  std::string not_an_element(const Eigen::MatrixXd& m, const std::string& name) const {
    const Element y(m);
    if (!y.template topRightCorner<kRows1, kRows2>().isZero(0.0) || !y.template bottomLeftCorner<kRows2, kRows1>().isZero(0.0))
      return name + " must be block diagonal, [[A, 0], [0, B]] with A in " + g1_.name() + " (" + std::to_string(kRows1) +
             " x " + std::to_string(kRows1) + ") and B in " + g2_.name() + " (" + std::to_string(kRows2) + " x " +
             std::to_string(kRows2) + ")";
    std::string why = g1_.not_an_element(Eigen::MatrixXd(first(y)), name + "'s " + g1_.name() + " block");
    return why.empty() ? g2_.not_an_element(Eigen::MatrixXd(second(y)), name + "'s " + g2_.name() + " block") : why;
  }
  std::string not_reachable(const Eigen::MatrixXd& y0, const Eigen::MatrixXd& z) const {
    const Element a(y0), b(z);
    std::string why = g1_.not_reachable(Eigen::MatrixXd(first(a)), Eigen::MatrixXd(first(b)));
    return why.empty() ? g2_.not_reachable(Eigen::MatrixXd(second(a)), Eigen::MatrixXd(second(b))) : why;
  }

 private:
  static typename G1::Element first(const Element& y) { return y.template topLeftCorner<kRows1, kRows1>(); }
  static typename G2::Element second(const Element& y) { return y.template bottomRightCorner<kRows2, kRows2>(); }
  static auto head(const Vector& v) { return typename G1::Vector(v.template head<kDim1>()); }
  static auto tail(const Vector& v) { return typename G2::Vector(v.template tail<kDim2>()); }
  static Element join(const typename G1::Element& a, const typename G2::Element& b) {
    Element m = Element::Zero();
    m.template topLeftCorner<kRows1, kRows1>() = a;
    m.template bottomRightCorner<kRows2, kRows2>() = b;
    return m;
  }
  static Vector stack(const typename G1::Vector& a, const typename G2::Vector& b) {
    Vector v;
    v << a, b;
    return v;
  }
  static Operator diagonal(const typename G1::Operator& a, const typename G2::Operator& b) {
    Operator m = Operator::Zero();
    m.template topLeftCorner<kDim1, kDim1>() = a;
    m.template bottomRightCorner<kDim2, kDim2>() = b;
    return m;
  }

  G1 g1_{};
  G2 g2_{};
};

}  // namespace lienewton
