// (SO(3) x R^3)^k, k rigid bodies with k chosen at run time (power_group.hpp), against truths that do not come
// from its own code: the body group SO3xR3Group applied block by block, and the compile-time product
// SO3xR3 x SO3xR3 x SO3xR3 (product_group.hpp) for k = 3, which must agree with it bit for bit. The battery every
// group passes (lie_group_properties_test.cpp) runs on it too. eps = 2^-52 (DBL_EPSILON).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "core/groups/mechanics_groups.hpp"

namespace lienewton {
namespace {

using G = SO3xR3PowerGroup;
using Body = SO3xR3Group;

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kPi = std::numbers::pi;

// Coordinates whose body i turns by angles[i] about a random axis, with an angular velocity of size ~1.
Eigen::VectorXd coordinates(const std::vector<double>& angles, std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  Eigen::VectorXd v(6 * static_cast<int>(angles.size()));
  for (std::size_t i = 0; i < angles.size(); ++i) {
    Eigen::Vector3d axis, w;
    for (int j = 0; j < 3; ++j) axis(j) = normal(rng), w(j) = normal(rng);
    v.segment<3>(6 * i) = angles[i] * axis.normalized();
    v.segment<3>(6 * i + 3) = w;
  }
  return v;
}

Body::Vector part(const Eigen::VectorXd& v, int i) { return v.segment<6>(6 * i); }
Eigen::MatrixXd dense(const G::Operator& m) { return Eigen::MatrixXd(m); }
// The block-diagonal matrix diag(y1, ..., yk) of a strip [y1 ... yk]: the compile-time product's element.
Eigen::MatrixXd diagonal(const Eigen::MatrixXd& strip) {
  const Eigen::Index r = strip.rows(), k = strip.cols() / r;
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(r * k, r * k);
  for (Eigen::Index i = 0; i < k; ++i) m.block(i * r, i * r, r, r) = strip.middleCols(i * r, r);
  return m;
}

TEST(PowerGroup, ShapeAndNameFollowTheBody) {
  const G g(8);
  EXPECT_EQ(g.name(), "(SO(3)xR^3)^8");
  EXPECT_EQ(g.n(), 8);
  EXPECT_EQ(g.dim(), 48);
  EXPECT_EQ(g.identity().rows(), 7);
  EXPECT_EQ(g.identity().cols(), 56);
  EXPECT_EQ(diagonal(g.matrix(g.identity())), Eigen::MatrixXd::Identity(56, 56));
  EXPECT_EQ(G::kAlgebraDimension, "6k");
  EXPECT_EQ(G::kLogRadius, kPi);
  EXPECT_EQ(std::string(G::kAngleName), "rotation angle");
}

// exp, log and the differentials are the body's, block by block, exactly (the same operations on the same
// blocks), and zero off the diagonal blocks: the Newton matrix of a field that couples no bodies stays block
// diagonal. Each body at its own angle, one of them near pi: log_vector's angle is the largest.
TEST(PowerGroup, EveryBlockIsTheBodys) {
  const G g(5);
  const Body body;
  std::mt19937_64 rng(11);
  const std::vector<double> angles = {0.0, 1e-9, 0.7, kPi - 1e-6, 2.5};
  const Eigen::VectorXd v = coordinates(angles, rng), u = coordinates({0.3, 0.3, 0.3, 0.3, 0.3}, rng);
  const G::Element y = g.exp(v);
  const G::Spectral s = g.spectral(v);
  const Eigen::MatrixXd dexp = dense(g.dexp_matrix(s)), dexpinv = dense(g.dexpinv_matrix(s)),
                        ad = dense(g.ad_matrix(v));
  Eigen::MatrixXd expected_y(7, 35);
  Eigen::MatrixXd expected_dexp = Eigen::MatrixXd::Zero(30, 30), expected_dexpinv = expected_dexp,
                  expected_ad = expected_dexp;
  for (int i = 0; i < 5; ++i) {
    const auto si = body.spectral(part(v, i));
    expected_y.middleCols<7>(7 * i) = body.exp(part(v, i));
    expected_dexp.block<6, 6>(6 * i, 6 * i) = body.dexp_matrix(si);
    expected_dexpinv.block<6, 6>(6 * i, 6 * i) = body.dexpinv_matrix(si);
    expected_ad.block<6, 6>(6 * i, 6 * i) = body.ad_matrix(part(v, i));
    EXPECT_EQ(part(g.dexp(s, u), i), body.dexp(si, part(u, i))) << "body " << i;
    EXPECT_EQ(part(g.dexpinv(s, u), i), body.dexpinv(si, part(u, i))) << "body " << i;
    EXPECT_EQ(part(g.bracket(v, u), i), body.bracket(part(v, i), part(u, i))) << "body " << i;
  }
  EXPECT_EQ(g.matrix(y), expected_y);
  EXPECT_EQ(g.element(expected_y), y);
  EXPECT_EQ(dexp, expected_dexp);
  EXPECT_EQ(dexpinv, expected_dexpinv);
  EXPECT_EQ(ad, expected_ad);
  EXPECT_LE(g.dexp_matrix(s).nonZeros(), 5 * 36);  // the sparse pattern holds the blocks alone

  double angle = -1.0;
  const Eigen::VectorXd back = g.log_vector(y, angle);
  EXPECT_EQ(angle, g.angle(g.log(y)));
  EXPECT_NEAR(angle, kPi - 1e-6, 1e-9);
  for (int i = 0; i < 5; ++i) {
    // log's condition grows like 1 / (pi - angle) near pi (product_group_test.cpp).
    const double tol = 8 * kEps / (kPi - angles[static_cast<std::size_t>(i)]) + 8 * kEps;
    EXPECT_LE((part(back, i) - part(v, i)).norm(), tol * std::max(1.0, part(v, i).norm())) << "body " << i;
  }
}

// dexp_v dexpinv_v = I to 16 k eps for every body near 0, inside and near pi (the matrices, as the Newton step
// uses them), and vee(hat(v)) = v exactly.
TEST(PowerGroup, DexpInvertsDexpinvAndVeeInvertsHat) {
  const G g(6);
  std::mt19937_64 rng(5);
  for (const std::vector<double>& angles : {std::vector<double>{0, 0, 0, 0, 0, 0},
                                             std::vector<double>{1e-12, 1e-6, 0.1, 1.0, 3.0, kPi - 1e-9}}) {
    const Eigen::VectorXd v = coordinates(angles, rng);
    const G::Spectral s = g.spectral(v);
    const Eigen::MatrixXd product = dense(g.dexp_matrix(s) * g.dexpinv_matrix(s));
    EXPECT_LE((product - Eigen::MatrixXd::Identity(36, 36)).norm(), 16 * g.n() * kEps);
    EXPECT_EQ(g.vee(g.hat(v)), v);
  }
}

// For k = 3 the power is the compile-time product of three bodies: the same matrices, spectral forms and seeded
// start, bit for bit, and the same defect to rounding.
TEST(PowerGroup, AgreesWithTheProductOfItsBodies) {
  using Three = ProductGroup<Body, Body, Body>;
  const G g(3);
  const Three p;
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd v = coordinates({0.1 * trial, 3.0 - 0.3 * trial, 1.0}, rng);
    const Eigen::VectorXd u = coordinates({0.5, 0.5, 0.5}, rng);
    const Three::Vector pv = v, pu = u;
    EXPECT_EQ(diagonal(g.matrix(g.exp(v))), p.exp(pv));
    EXPECT_EQ(diagonal(g.matrix(g.times_exp(g.exp(u), v))), p.times_exp(p.exp(pu), pv));
    EXPECT_EQ(dense(g.dexpinv_matrix(g.spectral(v))), p.dexpinv_matrix(p.spectral(pv)));
    EXPECT_EQ(dense(g.dexp_matrix(g.spectral(v))), p.dexp_matrix(p.spectral(pv)));
    EXPECT_EQ(g.vector(g.log(g.exp(v))), p.vector(p.log(p.exp(pv))));
    EXPECT_EQ(g.angle(g.spectral(v)), p.angle(p.spectral(pv)));
    const G::Element y = g.exp(v), w = g.hat(u);
    const Eigen::MatrixXd py = diagonal(g.matrix(y)), pw = diagonal(g.matrix(w));
    EXPECT_EQ(diagonal(g.matrix(g.tangent(y, w))), p.tangent(py, pw));
    EXPECT_EQ(diagonal(g.matrix(g.compose(y, g.inverse(y)))), p.compose(py, p.inverse(py)));
    // The bodies' defects only (a strip has nothing off the blocks), summed in another grouping.
    const G::Element off = y + 1e-3 * w;
    EXPECT_NEAR(g.defect(off), p.defect(diagonal(off)), 4 * kEps * p.defect(diagonal(off)));
  }
  for (std::uint64_t seed : {1u, 99u}) EXPECT_EQ(diagonal(g.matrix(g.random(seed))), p.random(seed)) << "seed " << seed;
}

// One body is the body group itself.
TEST(PowerGroup, OneBodyIsTheBodyGroup) {
  const G g(1);
  const Body body;
  std::mt19937_64 rng(1);
  const Eigen::VectorXd v = coordinates({2.0}, rng);
  EXPECT_EQ(g.matrix(g.exp(v)), Eigen::MatrixXd(body.exp(v)));
  EXPECT_EQ(g.matrix(g.random(7)), Eigen::MatrixXd(body.random(7)));
  EXPECT_EQ(dense(g.dexpinv_matrix(g.spectral(v))), Eigen::MatrixXd(body.dexpinv_matrix(body.spectral(v))));
}

// A request's matrix: accepted when it is the strip of k bodies; another shape, or one body that is not an
// element, is refused in words naming it; a y0 whose body turns the other way from z's (det -1 against det +1) is
// unreachable, naming the body.
TEST(PowerGroup, MembershipNamesTheBody) {
  const G g(4);
  const Eigen::MatrixXd z = g.matrix(g.random(3));
  EXPECT_EQ(z.rows(), 7);
  EXPECT_EQ(z.cols(), 28);
  EXPECT_EQ(g.not_an_element(z, "z"), "");
  EXPECT_EQ(g.not_an_element(diagonal(z), "z"), "z must be 4 elements of SO(3)xR^3 side by side (7 x 28)");
  Eigen::MatrixXd skewed = z;
  skewed(0, 7 * 2) += 1e-3;
  EXPECT_NE(g.not_an_element(skewed, "z").find("z's body 3"), std::string::npos) << g.not_an_element(skewed, "z");
  Eigen::MatrixXd flipped = z;
  flipped.block<3, 3>(0, 7) = -flipped.block<3, 3>(0, 7);
  EXPECT_EQ(g.not_reachable(z, z), "");
  EXPECT_EQ(g.not_reachable(flipped, z).rfind("body 2: ", 0), 0u) << g.not_reachable(flipped, z);
  EXPECT_GT(g.defect(g.element(skewed)), 0.9e-3);
  EXPECT_LE(g.defect(g.project(g.element(skewed))), 16 * g.n() * kEps);
}

}  // namespace
}  // namespace lienewton
