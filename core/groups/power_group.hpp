#pragma once
// B^k: k copies of one fixed-size body group B (SE(3) x R^6: k rigid bodies' poses and twists), k chosen at run
// time (docs/many_bodies.md). Everything is B's, body by body, as in ProductGroup (product_group.hpp), whose
// fixed factors this is for a k only known from a request: coordinates (v1, ..., vk), hat/vee, bracket and ad,
// exp, log (a B::Spectral per body), dexp and dexpinv, defect and projection, tangent, membership.
//
// Sizes grow like k, not k^2: an element is the strip [y1 ... yk] of body matrices side by side (its +, -, scalar
// multiples and Frobenius norm are those of diag(y1, ..., yk), so the solvers' distances are unchanged), and the
// operators (ad, dexp, dexpinv and the problems' dg) are sparse, block diagonal for the group, so that a Newton
// matrix keeps the couplings' sparsity. A request's matrix is the strip too (kRows x kRows k: 11 x 11k on
// (SE(3) x R^6)^k), so a result's size also grows like k. Generic code that multiplies elements as matrices (the
// paper's matrix problems, a user's program) is not defined on this group.
//
// Each body keeps B's log domain, so log is defined iff every body's is and the angle is the largest body's.
#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "body_frame.hpp"
#include "lie_group.hpp"
#include "single_group_family.hpp"

namespace lienewton {

template <LieGroup B>
class PowerGroup {
  static_assert(B::Element::RowsAtCompileTime > 0 && B::Vector::RowsAtCompileTime > 0, "the body is fixed-size");

 public:
  static constexpr int kRows = B::Element::RowsAtCompileTime;  // one body's matrix size
  static constexpr int kBodyDim = B::Vector::RowsAtCompileTime;
  using Body = B;
  using Element = Eigen::Matrix<double, kRows, Eigen::Dynamic>;
  using Vector = Eigen::VectorXd;
  using Operator = Eigen::SparseMatrix<double>;
  using Spectral = std::vector<typename B::Spectral>;

  static constexpr double kLogRadius = B::kLogRadius;
  static constexpr double kLogMargin = B::kLogMargin;
  static constexpr const char* kAngleName = B::kAngleName;
  static constexpr const char* kLogBoundaryName = B::kLogBoundaryName;
  static inline const std::string kAlgebraDimension = std::to_string(kBodyDim) + "k";

  // k >= 1 bodies; the request's n is k.
  explicit PowerGroup(int k) : k_(k) {}
  int n() const { return k_; }
  int bodies() const { return k_; }
  // Appended piece by piece: "(" + std::string(...) trips a false -Wrestrict in GCC 12 at -O3.
  std::string name() const {
    std::string out = "(";
    out += body_.name();
    out += ")^";
    out += std::to_string(k_);
    return out;
  }
  int dim() const { return kBodyDim * k_; }
  const B& body_group() const { return body_; }

  // Body i of an element (or of an algebra element in the same strip form), and of coordinates.
  static auto body(const Element& y, int i) { return y.template middleCols<kRows>(i * kRows); }
  static auto body(Element& y, int i) { return y.template middleCols<kRows>(i * kRows); }
  static auto part(const Vector& v, int i) { return v.template segment<kBodyDim>(i * kBodyDim); }
  static auto part(Vector& v, int i) { return v.template segment<kBodyDim>(i * kBodyDim); }

  Element identity() const { return join([&](int) { return body_.identity(); }); }
  Element compose(const Element& a, const Element& b) const {
    return join([&](int i) { return body_.compose(body(a, i), body(b, i)); });
  }
  Element inverse(const Element& a) const { return join([&](int i) { return body_.inverse(body(a, i)); }); }
  Element hat(const Vector& v) const { return join([&](int i) { return body_.hat(part(v, i)); }); }
  Vector vee(const Element& m) const { return stack([&](int i) { return body_.vee(body(m, i)); }); }
  Vector bracket(const Vector& a, const Vector& b) const {
    return stack([&](int i) { return body_.bracket(part(a, i), part(b, i)); });
  }
  Operator ad_matrix(const Vector& v) const { return diagonal([&](int i) { return body_.ad_matrix(part(v, i)); }); }

  Element exp(const Vector& v) const { return join([&](int i) { return body_.exp(part(v, i)); }); }
  Element times_exp(const Element& y, const Vector& v) const {
    return join([&](int i) { return body_.times_exp(body(y, i), part(v, i)); });
  }
  Spectral spectral(const Vector& v) const { return spectrals([&](int i) { return body_.spectral(part(v, i)); }); }
  Spectral log(const Element& y) const { return spectrals([&](int i) { return body_.log(body(y, i)); }); }
  Vector log_vector(const Element& y, double& angle) const {
    angle = 0.0;
    return stack([&](int i) {
      double body_angle = 0.0;
      const typename B::Vector v = body_.log_vector(body(y, i), body_angle);
      angle = larger(angle, body_angle);
      return v;
    });
  }
  Vector vector(const Spectral& s) const { return stack([&](int i) { return body_.vector(at(s, i)); }); }
  // The largest body's angle (each body's is already the largest of its bounded factors').
  double angle(const Spectral& s) const {
    double out = 0.0;
    for (const auto& b : s) out = larger(out, body_.angle(b));
    return out;
  }
  Vector dexp(const Spectral& s, const Vector& u) const {
    return stack([&](int i) { return body_.dexp(at(s, i), part(u, i)); });
  }
  Vector dexpinv(const Spectral& s, const Vector& u) const {
    return stack([&](int i) { return body_.dexpinv(at(s, i), part(u, i)); });
  }
  Operator dexp_matrix(const Spectral& s) const { return diagonal([&](int i) { return body_.dexp_matrix(at(s, i)); }); }
  Operator dexpinv_matrix(const Spectral& s) const {
    return diagonal([&](int i) { return body_.dexpinv_matrix(at(s, i)); });
  }

  double defect(const Element& y) const {
    double out = 0.0;
    for (int i = 0; i < k_; ++i) out = std::hypot(out, body_.defect(body(y, i)));
    return out;
  }
  Element project(const Element& y) const { return join([&](int i) { return body_.project(body(y, i)); }); }
  // Every body's axes at its position, where the body has both (SE(3) x R^6): what a picture of bodies draws.
  std::vector<BodyFrame> body_frames(const Element& y) const
    requires requires(const B& g, const typename B::Element& e) {
      g.rotation(e);
      g.position(e);
    }
  {
    std::vector<BodyFrame> out;
    for (int i = 0; i < k_; ++i) out.push_back({body_.rotation(body(y, i)), body_.position(body(y, i))});
    return out;
  }
  double principal_angle(double theta) const { return body_.principal_angle(theta); }
  Element tangent(const Element& y, const Element& u) const {
    return join([&](int i) { return body_.tangent(body(y, i), body(u, i)); });
  }

  // diag(y1, ..., yk), the square matrix a user's program reads (user_field/algebra_defect.hpp), and its blocks.
  Eigen::MatrixXd block_diagonal(const Element& y) const {
    Eigen::MatrixXd m = Eigen::MatrixXd::Zero(kRows * k_, kRows * k_);
    for (int i = 0; i < k_; ++i) m.block<kRows, kRows>(i * kRows, i * kRows) = body(y, i);
    return m;
  }
  Element diagonal_blocks(const Eigen::MatrixXd& m) const {
    return join([&](int i) { return m.block<kRows, kRows>(i * kRows, i * kRows); });
  }
  // A request's matrix is the strip itself (not_an_element has checked its shape).
  Element element(const Eigen::MatrixXd& m) const { return m; }
  Eigen::MatrixXd matrix(const Element& y) const { return y; }
  // Body i from the seed moved on i times by splitmix64's increment, as ProductGroup draws a repeated factor:
  // B^k and B x ... x B start in the same poses, and no two bodies in one.
  Element random(std::uint64_t seed) const {
    return join([&](int i) { return body_.random(seed + static_cast<std::uint64_t>(i) * 0x9E3779B97F4A7C15ull); });
  }
  // The strip's shape, each block an element of B (in B's words, naming the body).
  std::string not_an_element(const Eigen::MatrixXd& m, const std::string& name) const {
    if (m.rows() != kRows || m.cols() != kRows * k_)
      return name + " must be " + std::to_string(k_) + " elements of " + body_.name() + " side by side (" +
             std::to_string(kRows) + " x " + std::to_string(kRows * k_) + ")";
    for (int i = 0; i < k_; ++i) {
      const Eigen::MatrixXd block = m.middleCols<kRows>(i * kRows);
      if (std::string why = body_.not_an_element(block, name + "'s body " + std::to_string(i + 1)); !why.empty())
        return why;
    }
    return {};
  }
  std::string not_reachable(const Eigen::MatrixXd& y0, const Eigen::MatrixXd& z) const {
    for (int i = 0; i < k_; ++i) {
      const Eigen::MatrixXd a = y0.middleCols<kRows>(i * kRows), b = z.middleCols<kRows>(i * kRows);
      if (std::string why = body_.not_reachable(a, b); !why.empty())
        return "body " + std::to_string(i + 1) + ": " + why;
    }
    return {};
  }

 private:
  static const typename B::Spectral& at(const Spectral& s, int i) { return s[static_cast<std::size_t>(i)]; }
  // NaN, once met, stays: an angle that is not a number is not outgrown.
  static double larger(double a, double b) { return std::isnan(a) || b <= a ? a : b; }
  template <class F>
  Element join(F&& body_of) const {
    Element m(kRows, kRows * k_);
    for (int i = 0; i < k_; ++i) body(m, i) = body_of(i);
    return m;
  }
  template <class F>
  Vector stack(F&& part_of) const {
    Vector v(dim());
    for (int i = 0; i < k_; ++i) part(v, i) = part_of(i);
    return v;
  }
  // A block-diagonal sparse operator from the bodies' blocks (their zeros are kept out of the pattern).
  template <class F>
  Operator diagonal(F&& block_of) const {
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(static_cast<std::size_t>(k_) * kBodyDim * kBodyDim);
    for (int i = 0; i < k_; ++i) {
      const typename B::Operator block = block_of(i);
      for (int c = 0; c < kBodyDim; ++c)
        for (int r = 0; r < kBodyDim; ++r)
          if (block(r, c) != 0.0) entries.emplace_back(i * kBodyDim + r, i * kBodyDim + c, block(r, c));
    }
    Operator m(dim(), dim());
    m.setFromTriplets(entries.begin(), entries.end());
    return m;
  }
  template <class F>
  Spectral spectrals(F&& of) const {
    Spectral s;
    s.reserve(static_cast<std::size_t>(k_));
    for (int i = 0; i < k_; ++i) s.push_back(of(i));
    return s;
  }

  int k_;
  B body_{};
};

// The family of k bodies of B (register_group.hpp), k = n from 2 to MaxIndex: the Newton matrix is sparse but a
// result still carries k body matrices per iterate, so k is bounded per family rather than by --max-n.
template <FamilyName Name, LieGroup B, int MaxIndex>
struct PowerFamily {
  static constexpr const char* kName = Name.text;
  static constexpr int kMaxIndex = MaxIndex;
  template <class F>
  static decltype(auto) with_group(int n, F&& f) {
    return f(PowerGroup<B>(n));
  }
};

}  // namespace lienewton
