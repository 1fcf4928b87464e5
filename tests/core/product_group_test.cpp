// The product of more than one bounded factor: SO(3) x SO(3) x R^6, the state space of two rigid bodies (their
// rotations and angular velocities), against truths that do not come from the product's own code: Eigen's
// AngleAxis for exp, the matrix commutator for the bracket, central differences of exp for dexp (2.10) with the
// error's slope, and the factors' own answers block by block. eps = 2^-52 (DBL_EPSILON). The battery every group
// passes (lie_group_properties_test.cpp) runs on this product too.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "core/groups/mechanics_groups.hpp"

namespace lienewton {
namespace {

using G = SO3xSO3xR6Group;
using V = G::Vector;
using M = G::Element;

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kPi = std::numbers::pi;

// v with rotation vectors of angles a and b about fixed random axes, and a translation part of size ~1.
V coordinates(double a, double b, std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  Eigen::Vector3d axis1, axis2;
  for (int i = 0; i < 3; ++i) axis1(i) = normal(rng), axis2(i) = normal(rng);
  V v;
  v.segment<3>(0) = a * axis1.normalized();
  v.segment<3>(3) = b * axis2.normalized();
  for (int i = 6; i < 12; ++i) v(i) = normal(rng);
  return v;
}

Eigen::Matrix3d rodrigues(const Eigen::Vector3d& w) {
  const double t = w.norm();
  return t == 0 ? Eigen::Matrix3d::Identity() : Eigen::AngleAxisd(t, w / t).toRotationMatrix();
}

TEST(ProductGroup, ShapeAndNameFollowTheFactors) {
  const G g;
  EXPECT_EQ(g.name(), "SO(3)xSO(3)xR^6");
  EXPECT_EQ(g.dim(), 12);
  EXPECT_EQ(g.n(), 3);
  EXPECT_EQ(G::kAlgebraDimension, "12");
  EXPECT_EQ(M::RowsAtCompileTime, 13);
  EXPECT_EQ(G::kLogRadius, kPi);
  EXPECT_EQ(G::kLogMargin, kLogDomainMargin);
  EXPECT_EQ(std::string(G::kAngleName), "rotation angle");
  EXPECT_EQ(std::string(G::kLogBoundaryName), "pi");
}

// exp(v) is block diagonal with Rodrigues' rotations (Eigen's AngleAxis) and [[I, x], [0, 1]], to 8 eps per
// entry (each of the two within a few ulps); log(exp(v)) = v to 8 eps / (pi - angle) + 8 eps relative (log's condition grows like 1 / (pi - angle)),
// at angles near 0, inside and near pi in each rotation factor, the other factor anywhere; the product's angle
// is the larger of the two rotation angles, and log_vector's angle is log's.
TEST(ProductGroup, ExpLogRoundTripInEachFactorNearZeroAndPi) {
  const G g;
  std::mt19937_64 rng(7);
  const std::vector<double> angles = {0.0, 1e-12, 1e-6, 0.3, 2.0, 3.0, kPi - 1e-3, kPi - 1e-6};
  for (double a : angles) {
    for (double b : angles) {
      const V v = coordinates(a, b, rng);
      const M y = g.exp(v);
      M truth = M::Identity();
      truth.block<3, 3>(0, 0) = rodrigues(v.segment<3>(0));
      truth.block<3, 3>(3, 3) = rodrigues(v.segment<3>(3));
      truth.block<6, 1>(6, 12) = v.tail<6>();
      EXPECT_LE((y - truth).cwiseAbs().maxCoeff(), 8 * kEps) << "exp at angles " << a << ", " << b;

      double angle = -1;
      const V back = g.log_vector(y, angle);
      const auto tol = [](double t) { return 8 * kEps / (kPi - t) + 8 * kEps; };
      EXPECT_LE((back.segment<3>(0) - v.segment<3>(0)).norm(), tol(a) * std::max(1.0, a)) << a << ", " << b;
      EXPECT_LE((back.segment<3>(3) - v.segment<3>(3)).norm(), tol(b) * std::max(1.0, b)) << a << ", " << b;
      EXPECT_EQ(back.tail<6>(), v.tail<6>()) << "R^6's log is exact";
      EXPECT_NEAR(angle, std::max(a, b), tol(std::max(a, b)) * std::max(1.0, std::max(a, b)));
      EXPECT_EQ(angle, g.angle(g.log(y)));
      EXPECT_TRUE(inside_log_domain<G>(angle));
      const double larger = std::max(v.segment<3>(0).norm(), v.segment<3>(3).norm());
      EXPECT_NEAR(g.angle(g.spectral(v)), larger, 2 * kEps * larger);
    }
  }
}

// log is defined iff every factor's is: a half turn in either rotation factor alone is outside the domain.
TEST(ProductGroup, LogDomainIsEveryFactorsDomain) {
  const G g;
  const Eigen::Matrix3d half_turn = Eigen::Vector3d(1, -1, -1).asDiagonal();
  for (int factor = 0; factor < 2; ++factor) {
    M y = M::Identity();
    y.block<3, 3>(3 * factor, 3 * factor) = half_turn;
    double angle = 0;
    bool refused = false;
    try {
      angle = g.angle(g.log(y));
    } catch (const LogDomainError&) {
      refused = true;
    }
    EXPECT_TRUE(refused || !inside_log_domain<G>(angle)) << "half turn in rotation factor " << factor;
  }
}

// The q x q matrices are block diagonal exactly, each block its factor's own matrix, and the hat of v is too.
TEST(ProductGroup, MatricesAreBlockDiagonalFactorByFactor) {
  const G g;
  const SO3Group so3;
  std::mt19937_64 rng(11);
  const V v = coordinates(1.1, 2.9, rng);
  const auto s = g.spectral(v);
  for (const auto& [name, m, first, second] :
       {std::tuple{"ad", g.ad_matrix(v), so3.ad_matrix(v.segment<3>(0)), so3.ad_matrix(v.segment<3>(3))},
        std::tuple{"dexp", g.dexp_matrix(s), so3.dexp_matrix(v.segment<3>(0)), so3.dexp_matrix(v.segment<3>(3))},
        std::tuple{"dexpinv", g.dexpinv_matrix(s), so3.dexpinv_matrix(v.segment<3>(0)),
                   so3.dexpinv_matrix(v.segment<3>(3))}}) {
    G::Operator expected = G::Operator::Zero();
    expected.block<3, 3>(0, 0) = first;
    expected.block<3, 3>(3, 3) = second;
    if (std::string(name) != "ad") expected.block<6, 6>(6, 6).setIdentity();
    EXPECT_EQ(m, expected) << name;
  }
  M hat = M::Zero();
  hat.block<3, 3>(0, 0) = so3.hat(v.segment<3>(0));
  hat.block<3, 3>(3, 3) = so3.hat(v.segment<3>(3));
  hat.block<6, 1>(6, 12) = v.tail<6>();
  EXPECT_EQ(g.hat(v), hat);
  EXPECT_EQ(g.vee(hat), v);
}

// dexp_v o dexpinv_v = Id as matrices, to 64 eps, for rotation angles up to 3 in both factors (where dexpinv's
// norm is below 1 / (pi - 3) ~ 7).
TEST(ProductGroup, DexpAndDexpinvMatricesAreInverses) {
  const G g;
  std::mt19937_64 rng(13);
  for (double a : {0.0, 1e-8, 0.5, 2.0, 3.0}) {
    for (double b : {0.0, 1e-8, 0.5, 2.0, 3.0}) {
      const auto s = g.spectral(coordinates(a, b, rng));
      const G::Operator id = G::Operator::Identity();
      EXPECT_LE((g.dexp_matrix(s) * g.dexpinv_matrix(s) - id).norm(), 64 * kEps) << a << ", " << b;
      EXPECT_LE((g.dexpinv_matrix(s) * g.dexp_matrix(s) - id).norm(), 64 * kEps) << a << ", " << b;
    }
  }
}

// dexp (2.10) against central differences of exp: column j of the matrix is vee(exp(v)^-1 (exp(v + t e_j) -
// exp(v - t e_j)) / 2t) + O(t^2). At t = 1e-2 and 5e-3 the truncation error (~1e-5) dwarfs rounding
// (~eps / t), so halving t divides it by 4 (within 5 %: the next term is O(t^4)), and at t = 1e-4 it is
// below 1e-7.
TEST(ProductGroup, DexpMatrixAgainstDifferencesOfExpWithSlope) {
  const G g;
  std::mt19937_64 rng(17);
  const V v = coordinates(1.3, 2.6, rng);
  const G::Operator exact = g.dexp_matrix(g.spectral(v));
  const M y_inv = g.inverse(g.exp(v));
  const auto error = [&](double t) {
    G::Operator quotient;
    for (int j = 0; j < g.dim(); ++j) {
      const V e = V::Unit(j);
      quotient.col(j) = g.vee(y_inv * (g.exp(v + t * e) - g.exp(v - t * e)) / (2 * t));
    }
    return (quotient - exact).norm();
  };
  const double coarse = error(1e-2), fine = error(5e-3);
  EXPECT_NEAR(coarse / fine, 4.0, 0.2) << coarse << " then " << fine;
  EXPECT_LE(error(1e-4), 1e-7);
}

// [a, b] = -[b, a] and the Jacobi identity, to a few eps of the products' size, and [a, b] is the matrix
// commutator of the hats.
TEST(ProductGroup, BracketIsAntisymmetricAndSatisfiesJacobi) {
  const G g;
  std::mt19937_64 rng(19);
  for (int k = 0; k < 20; ++k) {
    const V a = coordinates(1.0, 2.0, rng), b = coordinates(0.5, 3.0, rng), c = coordinates(2.5, 0.1, rng);
    const double ab = a.norm() * b.norm();
    EXPECT_LE((g.bracket(a, b) + g.bracket(b, a)).norm(), 4 * kEps * ab);
    const V jacobi = g.bracket(a, g.bracket(b, c)) + g.bracket(b, g.bracket(c, a)) + g.bracket(c, g.bracket(a, b));
    EXPECT_LE(jacobi.norm(), 32 * kEps * ab * c.norm());
    const M commutator = g.hat(a) * g.hat(b) - g.hat(b) * g.hat(a);
    EXPECT_LE((g.hat(g.bracket(a, b)) - commutator).norm(), 8 * kEps * ab);
  }
}

// A seeded element is in the group (defect <= 8 eps), its two rotations are different bodies' poses, and the
// requests' refusals name the block at fault, in the factor's words.
TEST(ProductGroup, MembershipAndDefectBlockByBlock) {
  const G g;
  const M y = g.random(5);
  EXPECT_LE(g.defect(y), 8 * kEps);
  EXPECT_EQ(g.not_an_element(g.matrix(y), "z"), "");
  EXPECT_GT((y.block<3, 3>(0, 0) - y.block<3, 3>(3, 3)).norm(), 0.1) << "the second body starts elsewhere";
  EXPECT_EQ(g.not_reachable(g.matrix(y), g.matrix(g.random(6))), "");

  Eigen::MatrixXd coupled = g.matrix(y);
  coupled(2, 4) = 0.5;  // between the two rotation blocks
  EXPECT_GE(g.defect(g.element(coupled)), 0.5);
  EXPECT_EQ(g.not_an_element(coupled, "z"),
            "z must be block diagonal, [[A, 0, 0], [0, B, 0], [0, 0, C]] with A in SO(3) (3 x 3), B in SO(3) "
            "(3 x 3) and C in R^6 (7 x 7)");

  Eigen::MatrixXd stretched = g.matrix(y);
  stretched.block(3, 3, 3, 3) *= 1.01;
  EXPECT_NE(g.not_an_element(stretched, "z").find("z's SO(3) block"), std::string::npos);
  EXPECT_GT(g.defect(g.element(stretched)), 0.01);
  EXPECT_LE(g.defect(g.project(g.element(stretched))), 8 * kEps);

  Eigen::MatrixXd reflected = g.matrix(y);
  reflected.block(3, 3, 3, 3) *= -1;  // det -1: z may lie in O(3), but y0 must lie in z's component
  EXPECT_NE(g.not_reachable(reflected, g.matrix(y)), "");
}

}  // namespace
}  // namespace lienewton
