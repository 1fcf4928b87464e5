// The rotation-only properties of the rotation groups (planes of rotation, exactly pi, Haar-random rotations,
// orthogonality and det +1, skew logs, the Bernoulli series, typed errors outside SO(N)), as typed tests for
// the SO(3) closed forms (SO3Group) and the spectral SO(N) path (SONGroup) at N = 2, 3, 4, 7, 15. What every
// Lie group must satisfy (dexp o dexpinv = Id, difference checks, BCH, ...) is in lie_group_properties_test.cpp.
//
// Conventions checked: algebra coordinates (rotation vector for SO(3), the paper's basis E_ij - E_ji for SO(N)),
// left-trivialised differentials dexpinv_v(u) = d/dt log(exp(v) exp(t u)) at t = 0 (paper (3.12)),
// dexp_v = sum (-1)^k/(k+1)! ad_v^k (2.10), BCH (2.8).
// Every tolerance is stated where it is used; eps = 2^-52 (DBL_EPSILON).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <numbers>

#include "core/groups/so3_group.hpp"
#include "core/groups/son_group.hpp"
#include "core/groups/with_group.hpp"
#include "random_algebra.hpp"

namespace lienewton {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kPi = std::numbers::pi;

struct SO3Closed {
  using G = SO3Group;
  static G group() { return {}; }
  static constexpr int N = 3;
  static constexpr bool closed_form = true;
};
template <int n>
struct SON {
  using G = SONGroup;
  static G group() { return SONGroup(n); }
  static constexpr int N = n;
  static constexpr bool closed_form = false;
};

class CaseNames {
 public:
  template <class T>
  static std::string GetName(int) {
    if constexpr (T::closed_form) return "SO3ClosedForm";
    else return "SON" + std::to_string(T::N);
  }
};

template <class Case>
class RotationGroupProperties : public ::testing::Test {
 protected:
  using G = typename Case::G;
  using M = typename G::Element;
  using V = typename G::Vector;
  static constexpr int N = Case::N;

  G g = Case::group();
  std::mt19937_64 rng{20240601u + N};

  V random_direction() { return test::random_direction(g, rng); }
  V random_vector(double lo, double hi) { return test::random_vector(g, rng, lo, hi); }
  // Coordinates of a unit rotation generator in a random 2-plane: a b^T - b a^T with a, b orthonormal.
  // For SO(3) this is a rotation about the random axis a x b; for SO(N) its only rotation angle equals its norm.
  V random_plane() {
    std::normal_distribution<double> normal;
    Eigen::VectorXd a(N), b(N);
    for (int i = 0; i < N; ++i) a(i) = normal(rng), b(i) = normal(rng);
    a.normalize();
    b -= a.dot(b) * a;
    b.normalize();
    const Eigen::MatrixXd k = a * b.transpose() - b * a.transpose();
    return g.vee(M(k));
  }
  // Unit generators whose exp(theta .) rotates by theta in one plane: every coordinate axis, plus random planes.
  std::vector<V> axes() {
    std::vector<V> out;
    for (int i = 0; i < g.dim(); ++i) out.push_back(basis_vector(g, i));
    out.push_back(random_plane());
    out.push_back(random_plane());
    return out;
  }
  M random_rotation() {  // Haar-distributed: Q of a Gaussian matrix, sign-fixed, det +1
    std::normal_distribution<double> normal;
    Eigen::MatrixXd a(N, N);
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < N; ++j) a(i, j) = normal(rng);
    Eigen::HouseholderQR<Eigen::MatrixXd> qr(a);
    Eigen::MatrixXd q = qr.householderQ();
    for (int j = 0; j < N; ++j)
      if (qr.matrixQR()(j, j) < 0) q.col(j) = -q.col(j);
    if (q.determinant() < 0) q.col(0) = -q.col(0);
    return M(q);
  }
  M identity() const { return g.identity(); }

  V log(const M& r) const { return g.vector(g.log(r)); }
  V dexpinv(const V& v, const V& u) const { return g.dexpinv(g.spectral(v), u); }
  V dexp(const V& v, const V& u) const { return g.dexp(g.spectral(v), u); }
  // The skew matrix of log(R) as the implementation returns it.
  Eigen::MatrixXd log_matrix(const M& r) const {
    if constexpr (Case::closed_form) return so3::hat(so3::log(r));
    else return son::log(r);
  }

  static double rel(double err, double scale) { return scale == 0.0 ? err : err / scale; }
};

using Cases = ::testing::Types<SO3Closed, SON<2>, SON<3>, SON<4>, SON<7>, SON<15>>;
TYPED_TEST_SUITE(RotationGroupProperties, Cases, CaseNames);

// ---------------------------------------------------------------------------------------------------------
// exp / log round trips.

// log(exp v) = v and exp(log R) = R to <= 1e-14 relative (2-norm of coordinates resp. Frobenius norm) on the
// fixed edge set theta in {0, 1e-12, 1e-8, 1e-5, pi/2, pi - 1e-9} about every coordinate axis (every basis plane
// for SO(N)) and about random axes (random planes).
TYPED_TEST(RotationGroupProperties, RoundTripOnEdgeSet) {
  constexpr double kTol = 1e-14;
  const double angles[] = {0.0, 1e-12, 1e-8, 1e-5, kPi / 2, kPi - 1e-9};
  const auto axes = this->axes();
  for (std::size_t k = 0; k < axes.size(); ++k) {
    for (double theta : angles) {
      SCOPED_TRACE("axis #" + std::to_string(k) + ", theta = " + std::to_string(theta));
      const auto v = (theta * axes[k]).eval();
      const auto r = this->g.exp(v);
      typename TestFixture::V back;
      ASSERT_NO_THROW(back = this->log(r)) << "theta = " << theta;
      EXPECT_LE(this->rel((back - v).norm(), v.norm()), kTol) << "log(exp v) != v at theta = " << theta;
      const auto r2 = this->g.exp(back);
      EXPECT_LE((r2 - r).norm() / r.norm(), kTol) << "exp(log R) != R at theta = " << theta;
    }
  }
}

// Exactly pi about every coordinate axis / plane and random ones: R = I + 2 K^2 (K the unit generator) is
// symmetric, so its angle is pi to the last bit. SO(3) closed form: |log R| = pi (not 0), parallel to the axis,
// and exp(log R) = R. SO(N): log refuses with a typed LogDomainError reporting an angle at pi.
TYPED_TEST(RotationGroupProperties, ExactlyPi) {
  using M = typename TestFixture::M;
  for (const auto& axis : this->axes()) {
    const M k = this->g.hat(axis);
    const M r = M(this->identity() + 2.0 * k * k);
    ASSERT_LE(this->g.defect(r), 10 * kEps * TestFixture::N);  // the construction's own rounding
    if constexpr (TypeParam::closed_form) {
      const auto w = this->log(r);
      EXPECT_NEAR(w.norm(), kPi, 4 * kEps * kPi) << "log at exactly pi must have norm pi";
      EXPECT_LE(std::min((w - kPi * axis).norm(), (w + kPi * axis).norm()), 1e-14 * kPi) << "axis lost at pi";
      EXPECT_LE((this->g.exp(w) - r).norm() / r.norm(), 1e-14);
    } else {
      try {
        (void)this->g.log(r);
        ADD_FAILURE() << "log at exactly pi must be refused";
      } catch (const son::LogDomainError& e) {
        EXPECT_NEAR(e.angle(), kPi, son::kLogDomainMargin) << e.what();
      }
    }
  }
}

// Random inputs: v with |v| in (0, pi - 1e-3) (so every rotation angle is < pi), and Haar-random rotations.
TYPED_TEST(RotationGroupProperties, RoundTripOnRandomInputs) {
  constexpr double kTol = 1e-14;
  for (int trial = 0; trial < 200; ++trial) {
    const auto v = this->random_vector(1e-3, kPi - 1e-3);
    const auto r = this->g.exp(v);
    const auto back = this->log(r);
    EXPECT_LE((back - v).norm() / v.norm(), kTol) << "trial " << trial << ", |v| = " << v.norm();

    const auto haar = this->random_rotation();
    const auto w = this->log(haar);
    EXPECT_LE((this->g.exp(w) - haar).norm() / haar.norm(), kTol) << "trial " << trial;
  }
}

// exp(v) is orthogonal with det +1 to <= 10 N eps (Frobenius norm of R^T R - I, and |det R - 1|).
TYPED_TEST(RotationGroupProperties, ExpIsOrthogonalWithDetOne) {
  const double tol = 10.0 * TestFixture::N * kEps;
  std::vector<typename TestFixture::V> inputs;
  for (int trial = 0; trial < 100; ++trial) inputs.push_back(this->random_vector(0.0, 10.0));  // beyond pi too
  for (const auto& a : this->axes())
    for (double theta : {0.0, 1e-12, 1e-5, kPi / 2, kPi - 1e-9, kPi, 7.0}) inputs.push_back(theta * a);
  for (const auto& v : inputs) {
    const auto r = this->g.exp(v);
    EXPECT_LE(this->g.defect(r), tol) << "|v| = " << v.norm();
    EXPECT_LE(std::abs(Eigen::MatrixXd(r).determinant() - 1.0), tol) << "|v| = " << v.norm();
  }
}

// log(R) is skew to the last bit (the implementation's matrix, not a re-symmetrised copy).
TYPED_TEST(RotationGroupProperties, LogIsSkew) {
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::MatrixXd l = this->log_matrix(this->random_rotation());
    EXPECT_EQ((l + l.transpose()).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_EQ(l.diagonal().cwiseAbs().maxCoeff(), 0.0);
  }
}

// ---------------------------------------------------------------------------------------------------------
// Differentials.

// The Bernoulli series (3.9) truncated after ad_v^(2 p) converges to the exact dexpinv as p grows: for |v| = 0.5
// the eigenvalues of ad_v are at most 1 in modulus, the terms shrink by (1/2pi)^2 per order, so the relative
// error must decrease strictly with p until it reaches the rounding floor 8 N eps, and end <= 4 N eps at p = 11; p = 0 gives
// u + [v,u]/2, whose error is at most (2 |v|)^2/12.
TYPED_TEST(RotationGroupProperties, DexpinvSeriesConvergesToExact) {
  using V = typename TestFixture::V;
  const auto& g = this->g;
  for (int trial = 0; trial < 10; ++trial) {
    const V v = 0.5 * this->random_direction();
    const V u = this->random_direction();
    const V exact = this->dexpinv(v, u);
    const Eigen::MatrixXd vm = g.hat(v), um = g.hat(u);
    double previous = std::numeric_limits<double>::infinity();
    for (int p = 0; p <= 11; ++p) {
      const V series = g.vee(typename TestFixture::M(son::dexpinv_series(vm, um, p)));
      const double err = (series - exact).norm() / exact.norm();
      if (previous > 8.0 * TestFixture::N * kEps) {
        EXPECT_LT(err, previous) << "p = " << p << " did not improve";
      }
      if (p == 0) {
        EXPECT_LE(err, 0.09) << "p = 0";  // |B_2/2! ad_v^2| <= (2 max angle)^2/12 <= 1/12, |dexpinv_v(u)| >= |u|
      }
      if (p == 11) {
        EXPECT_LE(err, 4.0 * TestFixture::N * kEps) << "p = 11";
      }
      previous = err;
    }
  }
}

// Left-trivialisation and signs: dexp_v(u) = d/dt exp(v + t u) pulled back by exp(v)^-1, i.e.
// exp(v)^T (exp(v + t u) - exp(v - t u)) / 2t -> hat(dexp_v(u)), (2.10). Checked with the best of a few steps
// (central differences, error <= 1e-9 relative).
TYPED_TEST(RotationGroupProperties, DexpIsTheLeftTrivialisedDifferentialOfExp) {
  using V = typename TestFixture::V;
  using M = typename TestFixture::M;
  const auto& g = this->g;
  for (int trial = 0; trial < 8; ++trial) {
    const V v = this->random_vector(0.5, 2.5), u = this->random_direction();
    const V exact = this->dexp(v, u);
    double best = std::numeric_limits<double>::infinity();
    for (double t = 1e-3; t >= 1e-6; t /= 2) {
      const M d = g.inverse(g.exp(v)) * (g.exp((v + t * u).eval()) - g.exp((v - t * u).eval())) / (2 * t);
      best = std::min(best, (g.vee(d) - exact).norm() / exact.norm());
    }
    EXPECT_LE(best, 1e-9) << "trial " << trial;
  }
}

// log refuses matrices outside SO(N) with a typed son::LogDomainError, through the group interface the solvers
// use: not orthogonal, det -1, NaN, +-Inf.
TYPED_TEST(RotationGroupProperties, LogOutsideTheGroupThrowsTypedError) {
  using M = typename TestFixture::M;
  const M r = this->random_rotation();
  std::vector<std::pair<std::string, M>> bad;
  bad.emplace_back("not orthogonal (scaled by 1.01)", M(1.01 * r));
  M skewed = r;
  skewed(0, TestFixture::N - 1) += 1e-3;
  bad.emplace_back("not orthogonal (one entry +1e-3)", skewed);
  M reflected = r;
  reflected.col(0) = -reflected.col(0);
  bad.emplace_back("det -1", reflected);
  M nan = r;
  nan(TestFixture::N - 1, 0) = std::numeric_limits<double>::quiet_NaN();
  bad.emplace_back("NaN entry", nan);
  M inf = r;
  inf(0, 0) = std::numeric_limits<double>::infinity();
  bad.emplace_back("Inf entry", inf);
  for (const auto& [what, m] : bad) {
    try {
      (void)this->g.log(m);
      ADD_FAILURE() << "accepted: " << what;
    } catch (const son::LogDomainError& e) {
      // The message names the cause: a NaN or Inf entry is not reported as a mere orthogonality defect.
      const bool non_finite = what == "NaN entry" || what == "Inf entry";
      EXPECT_EQ(std::string(e.what()).find("non-finite") != std::string::npos, non_finite) << what << ": " << e.what();
    }
  }
}

}  // namespace
}  // namespace lienewton

namespace lienewton {
namespace {

// Titles and labels name the group the request picked: with_group's choice, by the group's own name.
TEST(RotationGroupNames, WithGroupPicksTheGroupATitleNames) {
  EXPECT_EQ(SO3Group{}.name(), "SO(3)");
  for (int n : {2, 3, 8, 64}) {
    EXPECT_EQ(with_group(n, [](const auto& g) { return g.name(); }), "SO(" + std::to_string(n) + ")");
    EXPECT_EQ(with_group(n, [](const auto& g) { return g.n(); }), n);
  }
}

}  // namespace
}  // namespace lienewton
