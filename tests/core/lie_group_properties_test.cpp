// The property battery every Lie group of the core must pass, through the LieGroup interface the solvers use
// (Sophus' LieGroupTests<G>, manif's MANIF_TEST): exp/log round trips inside log's domain, hat/vee, bracket
// antisymmetry and Jacobi, compose/inverse, the group's defect, dexp o dexpinv = Id, dexpinv and dexp against
// difference quotients of log and exp (3.12), (2.10), BCH to third order (2.8), and the matrices of dexp,
// dexpinv and ad against their actions; and what the requests ask of a group: its seeded element, the membership
// and projection of a request's matrix, the component identity and the distance to log's boundary. Adding a group =
// one LIE_GROUP_CASE line below. Rotation-only checks
// are in rotation_group_properties_test.cpp, so3_test.cpp and son_test.cpp. eps = 2^-52 (DBL_EPSILON).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "core/groups/mechanics_groups.hpp"
#include "core/groups/se3_group.hpp"
#include "core/groups/so3_group.hpp"
#include "core/groups/son_group.hpp"
#include "matrix_sum_group.hpp"
#include "random_algebra.hpp"
#include "rn_group.hpp"

namespace lienewton {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kPi = std::numbers::pi;

// One line per group: a name, the group, whether it is abelian (then BCH and the log quotients are exact).
#define LIE_GROUP_CASE(Name, make, is_abelian)                \
  struct Name {                                               \
    static auto group() { return make; }                      \
    static constexpr bool abelian = is_abelian;               \
    static std::string name() { return #Name; }               \
  }
LIE_GROUP_CASE(SO3ClosedForm, SO3Group{}, false);
LIE_GROUP_CASE(SO2, SONGroup(2), true);
LIE_GROUP_CASE(SO3Spectral, SONGroup(3), false);
LIE_GROUP_CASE(SO4, SONGroup(4), false);
LIE_GROUP_CASE(SO7, SONGroup(7), false);
LIE_GROUP_CASE(SO8, SONGroup(8), false);
LIE_GROUP_CASE(SO15, SONGroup(15), false);
LIE_GROUP_CASE(R5, RnGroup(5), true);
LIE_GROUP_CASE(Rnxn3, MatrixSumGroup(3), true);
LIE_GROUP_CASE(SE3, SE3Group{}, false);
LIE_GROUP_CASE(SO3xR3, SO3xR3Group{}, false);
LIE_GROUP_CASE(SE3xR6, SE3xR6Group{}, false);
LIE_GROUP_CASE(SO3xSO3xR6, SO3xSO3xR6Group{}, false);
LIE_GROUP_CASE(SO3xR3Power3, SO3xR3PowerGroup(3), false);
#undef LIE_GROUP_CASE

class CaseNames {
 public:
  template <class T>
  static std::string GetName(int) {
    return T::name();
  }
};

template <class Case>
class LieGroupProperties : public ::testing::Test {
 protected:
  using G = decltype(Case::group());
  using M = typename G::Element;
  using V = typename G::Vector;
  static_assert(LieGroup<G>);

  G g = Case::group();
  std::mt19937_64 rng{20240601u + static_cast<unsigned>(g.dim())};

  V random_direction() { return test::random_direction(g, rng); }
  V random_vector(double lo, double hi) { return test::random_vector(g, rng, lo, hi); }
  // Unit directions: every basis vector, plus two random planes a b^T - b a^T of a matrix group (one rotation
  // angle equal to the norm; in the rotation block of SE(n)), or two random directions.
  std::vector<V> axes() {
    std::vector<V> out;
    for (int i = 0; i < g.dim(); ++i) out.push_back(basis_vector(g, i));
    for (int k = 0; k < 2; ++k) {
      if constexpr (M::ColsAtCompileTime == 1) {
        out.push_back(random_direction());
      } else {
        std::normal_distribution<double> normal;
        const int n = g.n();
        Eigen::VectorXd a(n), b(n);
        for (int i = 0; i < n; ++i) a(i) = normal(rng), b(i) = normal(rng);
        a.normalize();
        b -= a.dot(b) * a;
        b.normalize();
        M plane = g.identity();  // the plane in the top left n x n block: all of SO(n)'s, SE(n)'s rotation block
        plane.setZero();
        plane.topLeftCorner(n, n) = a * b.transpose() - b * a.transpose();
        out.push_back(g.vee(plane));
      }
    }
    return out;
  }
  V log(const M& r) const { return g.vector(g.log(r)); }
  V dexpinv(const V& v, const V& u) const { return g.dexpinv(g.spectral(v), u); }
  V dexp(const V& v, const V& u) const { return g.dexp(g.spectral(v), u); }
  double norm(const M& y) const { return std::max(1.0, y.norm()); }
};

using Groups = ::testing::Types<SO3ClosedForm, SO2, SO3Spectral, SO4, SO7, SO8, SO15, R5, Rnxn3, SE3, SO3xR3, SE3xR6, SO3xSO3xR6,
                               SO3xR3Power3>;
TYPED_TEST_SUITE(LieGroupProperties, Groups, CaseNames);

// log(exp v) = v for |v| < pi - 1e-3 (inside log's domain on every rotation group) and exp(log y) = y, to
// <= 1e-14 relative, log_vector's angle within 1e-12 of log's; vector(spectral(v)) = v to <= 16 n eps relative (the spectral form's Schur rounding).
TYPED_TEST(LieGroupProperties, ExpLogRoundTrip) {
  for (int trial = 0; trial < 100; ++trial) {
    const auto v = this->random_vector(1e-3, kPi - 1e-3);
    const auto y = this->g.exp(v);
    const auto back = this->log(y);
    EXPECT_LE((back - v).norm() / v.norm(), 1e-14) << "log(exp v) at |v| = " << v.norm();
    EXPECT_LE((this->g.exp(back) - y).norm() / this->norm(y), 1e-14) << "exp(log y) at |v| = " << v.norm();
    EXPECT_LE((this->g.vector(this->g.spectral(v)) - v).norm() / v.norm(), 16.0 * this->g.n() * kEps);
    double angle = -1.0;
    const auto direct = this->g.log_vector(y, angle);
    EXPECT_LE((direct - v).norm() / v.norm(), 1e-14) << "log_vector";
    EXPECT_NEAR(angle, this->g.angle(this->g.log(y)), 1e-12) << "log_vector's angle";
    EXPECT_TRUE(inside_log_domain<typename TestFixture::G>(angle));
  }
}

// vee(hat(v)) = v to <= eps |v|.
TYPED_TEST(LieGroupProperties, HatVeeRoundTrip) {
  for (int trial = 0; trial < 50; ++trial) {
    const auto v = this->random_vector(0.1, 10.0);
    EXPECT_LE((this->g.vee(this->g.hat(v)) - v).norm(), kEps * v.norm());
  }
}

// [a, b] = -[b, a] and the Jacobi identity [a,[b,c]] + [b,[c,a]] + [c,[a,b]] = 0, to <= 16 n eps (unit vectors).
TYPED_TEST(LieGroupProperties, BracketIsAntisymmetricAndSatisfiesJacobi) {
  const auto& g = this->g;
  const double tol = 16.0 * g.n() * kEps;
  for (int trial = 0; trial < 50; ++trial) {
    const auto a = this->random_direction(), b = this->random_direction(), c = this->random_direction();
    EXPECT_LE((g.bracket(a, b) + g.bracket(b, a)).norm(), tol);
    EXPECT_LE((g.bracket(a, g.bracket(b, c)) + g.bracket(b, g.bracket(c, a)) + g.bracket(c, g.bracket(a, b))).norm(),
              tol);
    EXPECT_LE((g.ad_matrix(a) * b - g.bracket(a, b)).norm(), tol) << "ad_matrix(a) b != [a, b]";
  }
}

// y y^-1 = e, e y = y, (x y) z = x (y z) and y exp(v) = times_exp(y, v), to <= 16 n eps relative; the defect
// of exp(v) and of a product of 1000 times_exp factors stays <= 10 n eps resp. 1e-12.
TYPED_TEST(LieGroupProperties, ComposeInverseAndDefect) {
  const auto& g = this->g;
  const double tol = 16.0 * g.n() * kEps;
  auto y = g.identity();
  for (int trial = 0; trial < 50; ++trial) {
    const auto x = g.exp(this->random_vector(0.1, 3.0)), w = g.exp(this->random_vector(0.1, 3.0));
    const auto z = g.exp(this->random_vector(0.1, 3.0));
    const auto v = this->random_vector(0.1, 3.0);
    EXPECT_LE((g.compose(x, g.inverse(x)) - g.identity()).norm() / this->norm(x), tol);
    EXPECT_LE((g.compose(g.identity(), x) - x).norm() / this->norm(x), tol);
    EXPECT_LE((g.compose(g.compose(x, w), z) - g.compose(x, g.compose(w, z))).norm() / this->norm(x), tol);
    EXPECT_LE((g.times_exp(x, v) - g.compose(x, g.exp(v))).norm() / this->norm(x), tol);
    EXPECT_LE(g.defect(g.exp(v)), 10.0 * g.n() * kEps);
  }
  for (int k = 0; k < 1000; ++k) y = g.times_exp(y, this->random_vector(0.0, 1.0));
  EXPECT_LE(g.defect(y), 1e-12);
}

// The q x q matrices of dexp and dexpinv act as dexp and dexpinv do, to <= 16 n eps relative.
TYPED_TEST(LieGroupProperties, DifferentialMatricesMatchTheirActions) {
  const auto& g = this->g;
  for (int trial = 0; trial < 20; ++trial) {
    const auto v = this->random_vector(0.0, kPi - 1e-3), u = this->random_direction();
    const auto s = g.spectral(v);
    EXPECT_LE((g.dexp_matrix(s) * u - g.dexp(s, u)).norm(), 16.0 * g.n() * kEps);
    EXPECT_LE((g.dexpinv_matrix(s) * u - g.dexpinv(s, u)).norm() / g.dexpinv(s, u).norm(), 16.0 * g.n() * kEps);
  }
}

// dexp_v(u) = d/dt log(exp(v)^-1 exp(v + t u)) at t = 0 (2.10), against central differences: best error over
// t = 1e-3 ... 1e-6 <= 1e-9 relative.
TYPED_TEST(LieGroupProperties, DexpMatchesCentralDifferencesOfExp) {
  using V = typename TestFixture::V;
  const auto& g = this->g;
  for (int trial = 0; trial < 8; ++trial) {
    const V v = this->random_vector(0.5, 2.5), u = this->random_direction();
    const V exact = this->dexp(v, u);
    const auto back = g.inverse(g.exp(v));
    double best = std::numeric_limits<double>::infinity();
    for (double t = 1e-3; t >= 1e-6; t /= 2) {
      const V plus = this->log(g.compose(back, g.exp((v + t * u).eval())));
      const V minus = this->log(g.compose(back, g.exp((v - t * u).eval())));
      best = std::min(best, (V((plus - minus) / (2 * t)) - exact).norm() / exact.norm());
    }
    EXPECT_LE(best, 1e-9) << "trial " << trial;
  }
}

// dexp_v o dexpinv_v = Id and dexpinv_v o dexp_v = Id to <= 16 N eps relative, for |v| < pi (random and edges; |v| < pi keeps every rotation angle inside log's domain).
TYPED_TEST(LieGroupProperties, DexpInvertsDexpinv) {
  const double tol = 16.0 * this->g.n() * kEps;
  std::vector<typename TestFixture::V> vs;
  for (int trial = 0; trial < 100; ++trial) vs.push_back(this->random_vector(0.0, kPi - 1e-3));
  for (const auto& a : this->axes())
    for (double theta : {0.0, 1e-12, 1e-8, 1e-5, kPi / 2, kPi - 1e-9}) vs.push_back(theta * a);
  for (const auto& v : vs) {
    const auto u = this->random_vector(0.5, 2.0);
    const auto x = this->dexp(v, this->dexpinv(v, u));
    EXPECT_LE((x - u).norm() / u.norm(), tol) << "dexp o dexpinv at |v| = " << v.norm();
    const auto y = this->dexpinv(v, this->dexp(v, u));
    EXPECT_LE((y - u).norm() / u.norm(), tol) << "dexpinv o dexp at |v| = " << v.norm();
  }
}

// dexpinv_v(u) = d/dt log(exp(v) exp(t u)) at t = 0 (3.12), against central differences over a range of steps:
// while truncation dominates, the error must fall like t^2 (ratio 4 +- 0.5 per halving of t, for t = 0.1 ...
// 0.1/2^6), and the best error over t down to 1e-6 must reach <= 1e-9 relative (rounding-limited). An abelian group
// (SO(2), R^n): log(exp(v) exp(tu)) = v + t u is linear in t and every step must be exact to rounding
// (<= 8 eps (1 + |v|) / t relative).
TYPED_TEST(LieGroupProperties, DexpinvMatchesCentralDifferencesOfLog) {
  using V = typename TestFixture::V;
  for (int trial = 0; trial < 8; ++trial) {
    const V v = this->random_vector(0.5, 2.5);
    const V u = this->random_direction();
    const V exact = this->dexpinv(v, u);
    const auto ev = this->g.exp(v);
    auto central = [&](double t) {
      const V plus = this->log(this->g.compose(ev, this->g.exp((t * u).eval())));
      const V minus = this->log(this->g.compose(ev, this->g.exp((-t * u).eval())));
      return V((plus - minus) / (2 * t));
    };
    auto error = [&](double t) { return (central(t) - exact).norm() / exact.norm(); };
    if constexpr (TypeParam::abelian) {
      for (double t = 0.1; t > 1e-6; t /= 4) EXPECT_LE(error(t), 8 * kEps * (1 + v.norm()) / t) << "t = " << t;
      continue;
    }
    std::vector<double> errs;
    for (int k = 0; k <= 6; ++k) errs.push_back(error(0.1 * std::ldexp(1.0, -k)));
    for (std::size_t k = 0; k + 1 < errs.size(); ++k) {
      const double ratio = errs[k] / errs[k + 1];
      EXPECT_GT(ratio, 3.5) << "trial " << trial << ", step 0.1/2^" << k << ": errors " << errs[k] << " -> "
                            << errs[k + 1] << " do not fall like t^2";
      EXPECT_LT(ratio, 4.5) << "trial " << trial << ", step 0.1/2^" << k;
    }
    double best = std::numeric_limits<double>::infinity();
    for (double t = 1e-2; t >= 1e-6; t /= 2) best = std::min(best, error(t));
    EXPECT_LE(best, 1e-9) << "trial " << trial;
  }
}

// BCH to third order (2.8): log(exp(s u) exp(s v)) - [s(u + v) + s^2/2 [u,v] + s^3/12 ([u,[u,v]] + [v,[v,u]])]
// is O(s^4): halving s divides the error by 16 (accepted: 14 .. 18, s = 0.1 ... 0.1/2^4). An abelian group (SO(2), R^n): the
// remainder is zero to rounding (<= 8 eps |s (u + v)|).
TYPED_TEST(LieGroupProperties, BchToThirdOrder) {
  using V = typename TestFixture::V;
  const auto& g = this->g;
  for (int trial = 0; trial < 8; ++trial) {
    const V u = this->random_direction(), v = this->random_direction();
    auto remainder = [&](double s) {
      const V a = s * u, b = s * v;
      const V w = this->log(g.compose(g.exp(a), g.exp(b)));
      const V ab = g.bracket(a, b);
      const V series = a + b + 0.5 * ab + (g.bracket(a, ab) + g.bracket(b, g.bracket(b, a))) / 12.0;
      return (w - series).norm();
    };
    if constexpr (TypeParam::abelian) {
      for (double s = 0.1; s > 1e-3; s /= 2) EXPECT_LE(remainder(s), 8 * kEps * s * (u + v).norm() + 1e-300);
      continue;
    }
    std::vector<double> errs;
    for (int k = 0; k <= 4; ++k) errs.push_back(remainder(0.1 * std::ldexp(1.0, -k)));
    for (std::size_t k = 0; k + 1 < errs.size(); ++k) {
      const double ratio = errs[k] / errs[k + 1];
      EXPECT_GT(ratio, 14.0) << "trial " << trial << ", s = 0.1/2^" << k << ": " << errs[k] << " -> " << errs[k + 1];
      EXPECT_LT(ratio, 18.0) << "trial " << trial << ", s = 0.1/2^" << k;
    }
  }
}

// The seeded element is an element (accepted as a request's z, defect at rounding), the same for the same seed and
// another for another; element and matrix convert a request's matrix exactly; y0 = z is reachable from z.
TYPED_TEST(LieGroupProperties, RandomElementIsAMember) {
  const auto& g = this->g;
  for (std::uint64_t seed : {1u, 2u, 12345u}) {
    const auto y = g.random(seed);
    const Eigen::MatrixXd m = g.matrix(y);
    EXPECT_EQ(g.not_an_element(m, "z"), "") << "seed " << seed;
    EXPECT_LE(g.defect(y), 16.0 * g.n() * kEps) << "seed " << seed;
    EXPECT_EQ(g.matrix(g.random(seed)), m) << "seed " << seed;
    EXPECT_NE(g.matrix(g.random(seed + 1)), m) << "seed " << seed;
    EXPECT_EQ(g.matrix(g.element(m)), m);
    EXPECT_EQ(g.not_reachable(m, m), "");
  }
}

// A member perturbed by 1e-6 projects back onto the group (accepted, defect at rounding) within a few times the
// perturbation; a member is its own projection to rounding.
TYPED_TEST(LieGroupProperties, ProjectionOfAPerturbedElementIsAMember) {
  const auto& g = this->g;
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 10; ++trial) {
    const auto y = g.exp(this->random_vector(0.1, 3.0));
    typename TestFixture::M noisy = y;
    for (Eigen::Index i = 0; i < noisy.size(); ++i) noisy.data()[i] += 1e-6 * normal(this->rng);
    const auto p = g.project(noisy);
    EXPECT_EQ(g.not_an_element(g.matrix(p), "y0"), "");
    EXPECT_LE(g.defect(p), 16.0 * g.n() * kEps);
    EXPECT_LE((p - y).norm(), 1e-5 * std::sqrt(double(y.size())));
    EXPECT_LE((g.project(y) - y).norm(), 16.0 * g.n() * kEps * this->norm(y));
  }
}

// tangent(y, U) = d/dt y exp(tU) at t = 0 (what the problems' differentials take), against central differences of
// times_exp at t = 1e-5: truncation ~t^2 and rounding ~eps/t, so <= 1e-8 relative.
TYPED_TEST(LieGroupProperties, TangentIsTheDerivativeOfTimesExp) {
  using M = typename TestFixture::M;
  using V = typename TestFixture::V;
  const auto& g = this->g;
  const double t = 1e-5;
  for (int trial = 0; trial < 10; ++trial) {
    const M y = g.exp(this->random_vector(0.1, 3.0));
    const V u = this->random_direction();
    const M exact = g.tangent(y, M(g.hat(u)));
    const M central = (g.times_exp(y, V(t * u)) - g.times_exp(y, V(-t * u))) / (2 * t);
    EXPECT_LE((central - exact).norm() / std::max(1.0, exact.norm()), 1e-8) << "trial " << trial;
  }
}

// The identity is at the full log radius from log's boundary, inside the domain, its own component's identity; the
// principal angle of a v inside the domain is v's own angle, and every principal angle lies in [0, kLogRadius].
TYPED_TEST(LieGroupProperties, LogBoundaryAndPrincipalAngle) {
  using G = typename TestFixture::G;
  const auto& g = this->g;
  const auto e = g.identity();
  const double at_identity = g.angle(g.log(e));
  EXPECT_EQ(at_identity, 0.0);
  EXPECT_EQ(log_boundary_distance<G>(at_identity), G::kLogRadius);
  EXPECT_TRUE(inside_log_domain<G>(at_identity));
  EXPECT_FALSE(std::string(G::kAlgebraDimension).empty());
  for (int trial = 0; trial < 20; ++trial) {
    const double angle = g.angle(g.spectral(this->random_vector(0.0, kPi - 1e-3)));
    EXPECT_EQ(g.principal_angle(angle), angle);
    const double far = g.principal_angle(g.angle(g.spectral(this->random_vector(0.0, 50.0))));
    EXPECT_GE(far, 0.0);
    EXPECT_LE(far, G::kLogRadius);
  }
}

}  // namespace
}  // namespace lienewton
