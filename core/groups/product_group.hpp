#pragma once
// The direct product G1 x ... x Gk of matrix groups (manif's Bundle), as block-diagonal matrices
// [[y1, 0, ...], [0, y2, ...], ...]: the product is the matrix product, and everything else comes from the factors
// block by block: coordinates (v1, ..., vk), hat/vee, bracket and ad (block-diagonal), exp, log (a Spectral per
// factor), dexp (2.10) and dexpinv (3.9) and their matrices (block-diagonal, so the Newton system is the factors'
// side by side), defect and projection, tangent, membership.
//
// Each factor keeps its own log domain, so the product's log is defined iff every factor's is. Factors with a
// global log (R^k, translation_group.hpp) add nothing to it; the bounded ones must share one radius, margin and
// words (SO(3) and SE(3): rotation angle, pi), so that the product's angle is the largest of theirs and every
// word a reason says about it is true of the factor that has it. SO(3) x R^3 is thus SO(3)'s domain exactly, and
// SO(3) x SO(3) x R^6 is inside log's domain while both rotation angles are below pi.
#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>

#include "lie_group.hpp"

namespace lienewton {

namespace product_detail {

constexpr bool bounded(double log_radius) { return log_radius < std::numeric_limits<double>::infinity(); }

// The factor whose log domain the product's words describe: the first bounded one (the first, if none is).
template <class... G>
constexpr std::size_t first_bounded() {
  constexpr double radii[] = {G::kLogRadius...};
  for (std::size_t i = 0; i < sizeof...(G); ++i)
    if (bounded(radii[i])) return i;
  return 0;
}

template <std::size_t K>
constexpr std::array<int, K> offsets(const std::array<int, K>& sizes) {
  std::array<int, K> at{};
  for (std::size_t i = 1; i < K; ++i) at[i] = at[i - 1] + sizes[i - 1];
  return at;
}

}  // namespace product_detail

template <LieGroup... G>
struct ProductGroup {
  static constexpr std::size_t kFactors = sizeof...(G);
  static_assert(kFactors >= 2, "a product has at least two factors");
  static_assert(((G::Element::RowsAtCompileTime > 0 && G::Vector::RowsAtCompileTime > 0) && ...),
                "the factors are fixed-size groups");
  template <std::size_t I>
  using Factor = std::tuple_element_t<I, std::tuple<G...>>;

  static constexpr std::array<int, kFactors> kRows{G::Element::RowsAtCompileTime...};
  static constexpr std::array<int, kFactors> kDims{G::Vector::RowsAtCompileTime...};
  static constexpr std::array<int, kFactors> kRowAt = product_detail::offsets(kRows);
  static constexpr std::array<int, kFactors> kDimAt = product_detail::offsets(kDims);
  static constexpr int kSize = (static_cast<int>(G::Element::RowsAtCompileTime) + ...);
  static constexpr int kDim = (static_cast<int>(G::Vector::RowsAtCompileTime) + ...);

  using Element = Eigen::Matrix<double, kSize, kSize>;
  using Vector = Eigen::Matrix<double, kDim, 1>;
  using Operator = Eigen::Matrix<double, kDim, kDim>;
  using Spectral = std::tuple<typename G::Spectral...>;

  using Measure = Factor<product_detail::first_bounded<G...>()>;
  static constexpr double kLogRadius = Measure::kLogRadius;
  static constexpr double kLogMargin = Measure::kLogMargin;
  static constexpr const char* kAngleName = Measure::kAngleName;
  static constexpr const char* kLogBoundaryName = Measure::kLogBoundaryName;
  static_assert(((!product_detail::bounded(G::kLogRadius) ||
                  (G::kLogRadius == kLogRadius && G::kLogMargin == kLogMargin &&
                   std::string_view(G::kAngleName) == kAngleName &&
                   std::string_view(G::kLogBoundaryName) == kLogBoundaryName)) &&
                 ...),
                "the bounded factors share one log radius, margin and words: the product's angle is the largest "
                "of theirs");
  static inline const std::string kAlgebraDimension = std::to_string(kDim);

  int n() const { return factor<0>().n(); }
  std::string name() const {
    std::string out;
    each([&](auto i) {
      if (i > 0) out += 'x';
      out += factor<i>().name();
    });
    return out;
  }
  int dim() const { return kDim; }
  Element identity() const { return Element::Identity(); }
  Element compose(const Element& a, const Element& b) const {
    return join([&](auto i) { return factor<i>().compose(block<i>(a), block<i>(b)); });
  }
  Element inverse(const Element& a) const { return join([&](auto i) { return factor<i>().inverse(block<i>(a)); }); }
  Element hat(const Vector& v) const { return join([&](auto i) { return factor<i>().hat(part<i>(v)); }); }
  Vector vee(const Element& m) const { return stack([&](auto i) { return factor<i>().vee(block<i>(m)); }); }
  Vector bracket(const Vector& a, const Vector& b) const {
    return stack([&](auto i) { return factor<i>().bracket(part<i>(a), part<i>(b)); });
  }
  Operator ad_matrix(const Vector& v) const {
    return diagonal([&](auto i) { return factor<i>().ad_matrix(part<i>(v)); });
  }

  Element exp(const Vector& v) const { return join([&](auto i) { return factor<i>().exp(part<i>(v)); }); }
  Element times_exp(const Element& y, const Vector& v) const {
    return join([&](auto i) { return factor<i>().times_exp(block<i>(y), part<i>(v)); });
  }
  Spectral spectral(const Vector& v) const {
    return spectrals([&](auto i) { return factor<i>().spectral(part<i>(v)); });
  }
  Spectral log(const Element& y) const { return spectrals([&](auto i) { return factor<i>().log(block<i>(y)); }); }
  Vector log_vector(const Element& y, double& angle) const {
    std::array<double, kFactors> angles{};
    const Vector v = stack([&](auto i) { return factor<i>().log_vector(block<i>(y), angles[i]); });
    angle = largest(angles);
    return v;
  }
  Vector vector(const Spectral& s) const { return stack([&](auto i) { return factor<i>().vector(std::get<i>(s)); }); }
  // The largest of the bounded factors' angles (0 when none is bounded).
  double angle(const Spectral& s) const {
    std::array<double, kFactors> angles{};
    each([&](auto i) { angles[i] = factor<i>().angle(std::get<i>(s)); });
    return largest(angles);
  }
  Vector dexp(const Spectral& s, const Vector& u) const {
    return stack([&](auto i) { return factor<i>().dexp(std::get<i>(s), part<i>(u)); });
  }
  Vector dexpinv(const Spectral& s, const Vector& u) const {
    return stack([&](auto i) { return factor<i>().dexpinv(std::get<i>(s), part<i>(u)); });
  }
  Operator dexp_matrix(const Spectral& s) const {
    return diagonal([&](auto i) { return factor<i>().dexp_matrix(std::get<i>(s)); });
  }
  Operator dexpinv_matrix(const Spectral& s) const {
    return diagonal([&](auto i) { return factor<i>().dexpinv_matrix(std::get<i>(s)); });
  }

  // The factors' defects and the off-diagonal blocks' size, together.
  double defect(const Element& y) const {
    double factors = 0.0, off = 0.0;
    each([&](auto i) {
      factors = std::hypot(factors, factor<i>().defect(block<i>(y)));
      if constexpr (i + 1 < kFactors) off = std::hypot(off, std::hypot(right_of<i>(y).norm(), below<i>(y).norm()));
    });
    return std::hypot(factors, off);
  }
  Element project(const Element& y) const { return join([&](auto i) { return factor<i>().project(block<i>(y)); }); }
  // The rotation of the first factor, where it has one (SO(3) x R^3: R; SE(3) x R^6: T's R).
  Eigen::Matrix3d rotation(const Element& y) const
    requires requires(const Factor<0>& g, const typename Factor<0>::Element& e) { g.rotation(e); }
  {
    return factor<0>().rotation(block<0>(y));
  }
  // The position of the first factor, where it has one (SE(3) x R^6: T's p).
  Eigen::Vector3d position(const Element& y) const
    requires requires(const Factor<0>& g, const typename Factor<0>::Element& e) { g.position(e); }
  {
    return factor<0>().position(block<0>(y));
  }
  // As on SO(N), whose angle is also the largest of several: the wrap of the bounded factors' common angle.
  double principal_angle(double theta) const { return Measure{}.principal_angle(theta); }
  Element tangent(const Element& y, const Element& u) const {
    return join([&](auto i) { return factor<i>().tangent(block<i>(y), block<i>(u)); });
  }

  Element element(const Eigen::MatrixXd& m) const { return Element(m); }
  Eigen::MatrixXd matrix(const Element& y) const { return Eigen::MatrixXd(y); }
  // Each factor its own seeded element; a factor repeating an earlier one's group draws from the seed moved on
  // by its repetition (splitmix64's increment), so that two rigid bodies do not start in one pose.
  Element random(std::uint64_t seed) const {
    return join([&](auto i) { return factor<i>().random(seed + repetition<i>() * 0x9E3779B97F4A7C15ull); });
  }
  // Block diagonal exactly, each block its factor's element (in the factor's words, naming the block).
  std::string not_an_element(const Eigen::MatrixXd& m, const std::string& name) const {
    const Element y(m);
    bool diagonal_blocks = true;
    each([&](auto i) {
      if constexpr (i + 1 < kFactors)
        diagonal_blocks = diagonal_blocks && right_of<i>(y).isZero(0.0) && below<i>(y).isZero(0.0);
    });
    if (!diagonal_blocks) return name + " must be block diagonal, " + block_pattern();
    std::string why;
    each([&](auto i) {
      if (why.empty())
        why = factor<i>().not_an_element(Eigen::MatrixXd(block<i>(y)), name + "'s " + factor<i>().name() + " block");
    });
    return why;
  }
  std::string not_reachable(const Eigen::MatrixXd& y0, const Eigen::MatrixXd& z) const {
    const Element a(y0), b(z);
    std::string why;
    each([&](auto i) {
      if (why.empty()) why = factor<i>().not_reachable(Eigen::MatrixXd(block<i>(a)), Eigen::MatrixXd(block<i>(b)));
    });
    return why;
  }

 private:
  template <class F>
  static void each(F&& f) {
    [&]<std::size_t... I>(std::index_sequence<I...>) {
      (f(std::integral_constant<std::size_t, I>{}), ...);
    }(std::index_sequence_for<G...>{});
  }
  template <std::size_t I>
  const Factor<I>& factor() const {
    return std::get<I>(factors_);
  }
  template <std::size_t I>
  static typename Factor<I>::Element block(const Element& y) {
    return y.template block<kRows[I], kRows[I]>(kRowAt[I], kRowAt[I]);
  }
  template <std::size_t I>
  static typename Factor<I>::Vector part(const Vector& v) {
    return v.template segment<kDims[I]>(kDimAt[I]);
  }
  // The off-diagonal strips beside and below block I (the rest of its rows and columns).
  template <std::size_t I>
  static auto right_of(const Element& y) {
    return y.template block<kRows[I], kSize - kRowAt[I] - kRows[I]>(kRowAt[I], kRowAt[I] + kRows[I]);
  }
  template <std::size_t I>
  static auto below(const Element& y) {
    return y.template block<kSize - kRowAt[I] - kRows[I], kRows[I]>(kRowAt[I] + kRows[I], kRowAt[I]);
  }
  template <std::size_t I>
  static constexpr std::uint64_t repetition() {
    return [&]<std::size_t... J>(std::index_sequence<J...>) {
      return (std::uint64_t{std::is_same_v<Factor<J>, Factor<I>>} + ... + 0);
    }(std::make_index_sequence<I>{});
  }
  static double largest(const std::array<double, kFactors>& angles) {
    double out = 0.0;
    bool first = true;
    each([&](auto i) {
      if constexpr (product_detail::bounded(Factor<i>::kLogRadius)) {
        if (first || std::isnan(angles[i]) || angles[i] > out) out = angles[i];  // a NaN angle stays NaN
        first = false;
      }
    });
    return out;
  }
  // [[A, 0], [0, B]] with A in SO(3) (3 x 3) and B in R^3 (4 x 4).
  std::string block_pattern() const {
    std::string rows, which;
    each([&](auto i) {
      const std::string letter(1, static_cast<char>('A' + i));
      std::string row;
      for (std::size_t j = 0; j < kFactors; ++j) row += (j == 0 ? "" : ", ") + (j == i ? letter : std::string("0"));
      rows += (i == 0 ? "[" : ", [") + row + "]";
      which += (i == 0 ? "" : i + 1 == kFactors ? " and " : ", ") + letter + " in " + factor<i>().name() + " (" +
               std::to_string(kRows[i]) + " x " + std::to_string(kRows[i]) + ")";
    });
    return "[" + rows + "] with " + which;
  }
  template <class F>
  static Element join(F&& block_of) {
    Element m = Element::Zero();
    each([&](auto i) { m.template block<kRows[i], kRows[i]>(kRowAt[i], kRowAt[i]) = block_of(i); });
    return m;
  }
  template <class F>
  static Vector stack(F&& part_of) {
    Vector v;
    each([&](auto i) { v.template segment<kDims[i]>(kDimAt[i]) = part_of(i); });
    return v;
  }
  template <class F>
  static Operator diagonal(F&& block_of) {
    Operator m = Operator::Zero();
    each([&](auto i) { m.template block<kDims[i], kDims[i]>(kDimAt[i], kDimAt[i]) = block_of(i); });
    return m;
  }
  template <class F>
  static Spectral spectrals(F&& of) {
    return [&]<std::size_t... I>(std::index_sequence<I...>) {
      return Spectral{of(std::integral_constant<std::size_t, I>{})...};
    }(std::index_sequence_for<G...>{});
  }

  std::tuple<G...> factors_{};
};

}  // namespace lienewton
