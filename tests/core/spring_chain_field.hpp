#pragma once
// A test field on (SE(3) x R^6)^k whose dg is block tridiagonal: body i's g reads its own matrix entries and, through
// a linear spring, its neighbours' (c (y_{i-1} - 2 y_i + y_{i+1}), read by a second map). g is linear in the entries of
// the strip y, so dg_y(u) = g(tangent(y, hat u)) exactly; coupling 0 leaves k independent bodies.
#include <Eigen/Dense>
#include <cmath>

#include "core/groups/mechanics_groups.hpp"
#include "core/problems.hpp"

namespace lienewton::test {

class SpringChain final : public VectorField<SE3xR6PowerGroup> {
 public:
  using G = SE3xR6PowerGroup;
  static constexpr int kRows = G::kRows, kDim = G::kBodyDim;
  using Map = Eigen::Matrix<double, kDim, kRows * kRows>;

  SpringChain(const G& group, double coupling) : group_(group), coupling_(coupling) {
    // Fixed, smooth, small entries: each body's own map and the spring's, alike for every body.
    for (int r = 0; r < kDim; ++r)
      for (int c = 0; c < kRows * kRows; ++c) {
        own_(r, c) = 0.05 * std::sin(1.7 * r + 0.3 * c + 1.0);
        spring_(r, c) = 0.05 * std::cos(0.9 * r - 0.7 * c);
      }
  }
  Vector g(const Element& y) const override { return apply(y); }
  Vector dg(const Element& y, const Vector& u) const override { return apply(group_.tangent(y, group_.hat(u))); }

 private:
  Vector apply(const Element& m) const {
    const int k = group_.bodies();
    Vector out(kDim * k);
    for (int i = 0; i < k; ++i) {
      out.segment<kDim>(kDim * i) = own_ * entries(m, i);
      if (coupling_ == 0.0) continue;
      Eigen::Matrix<double, kRows * kRows, 1> stretch = -2.0 * entries(m, i);
      if (i > 0) stretch += entries(m, i - 1);
      if (i + 1 < k) stretch += entries(m, i + 1);
      out.segment<kDim>(kDim * i) += coupling_ * (spring_ * stretch);
    }
    return out;
  }
  static Eigen::Matrix<double, kRows * kRows, 1> entries(const Element& m, int i) {
    const Eigen::Matrix<double, kRows, kRows> body = G::body(m, i);
    return Eigen::Map<const Eigen::Matrix<double, kRows * kRows, 1>>(body.data());
  }

  G group_;
  double coupling_;
  Map own_, spring_;
};

}  // namespace lienewton::test
