// The chain (core/chain.hpp) on (SE(3) x R^6)^k: its exact dg against central differences of g (error falling like
// t^2), dg's block-tridiagonal pattern, the energy balance dE/dt = -c sum |d_j'|^2 along the field, the hanging
// chain's static sag as an equilibrium, its start, and the groups it is defined on.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <random>
#include <vector>

#include "core/chain.hpp"
#include "core/groups/so3.hpp"
#include "core/groups/son_group.hpp"
#include "core/problems.hpp"
#include "core/request_error.hpp"
#include "core/solvers/eigenvalues.hpp"
#include "core/validation.hpp"
#include "tests/core/chain_flat_reference.hpp"
#include "tests/core/random_algebra.hpp"

namespace lienewton {
namespace {

using Group = SE3xR6PowerGroup;
using Element = Group::Element;

// A state near the default start: every link moved by up to ~0.05 in each coordinate (poses off the straight line,
// joints open by centimetres) and turning and moving at ~1 rad/s and ~1 m/s.
Element shaken(const Chain& chain, int k, std::uint64_t seed) {
  const Group group(k);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  Eigen::VectorXd u(group.dim());
  for (int i = 0; i < group.dim(); ++i) u(i) = (i % 12 < 6 ? 0.05 : 1.0) * normal(rng);
  return group.times_exp(chain.start_strip(k), u);
}

// Central differences of g along y exp(t u), for every column of dg.
Eigen::MatrixXd central_differences(const Chain& chain, const Element& y, double t) {
  const Group group(Chain::links(y));
  Eigen::MatrixXd m(group.dim(), group.dim());
  for (int j = 0; j < group.dim(); ++j) {
    const Eigen::VectorXd u = basis_vector(group, j);
    m.col(j) = (chain.coordinates(group.times_exp(y, t * u)) - chain.coordinates(group.times_exp(y, -t * u))) / (2 * t);
  }
  return m;
}

TEST(Chain, ExactDifferentialMatchesCentralDifferencesWithSlopeTwo) {
  const Chain chain{ChainParams{}};
  for (int k : {2, 5})
    for (std::uint64_t seed : {1u, 2u}) {
      const Group group(k);
      const Element y = shaken(chain, k, seed);
      const Eigen::MatrixXd exact(chain.dg_matrix(group, y));
      std::vector<double> err;
      for (double t : {1e-3, 5e-4, 2.5e-4})
        err.push_back((central_differences(chain, y, t) - exact).norm() / exact.norm());
      EXPECT_NEAR(err[0] / err[1], 4.0, 0.4) << "k " << k << " seed " << seed;
      EXPECT_NEAR(err[1] / err[2], 4.0, 0.4) << "k " << k << " seed " << seed;
      EXPECT_LT(err[2], 1e-6) << "k " << k << " seed " << seed;
      // dg as the field applies it is the matrix's product
      std::mt19937_64 rng(seed);
      const Eigen::VectorXd u = test::random_direction(group, rng);
      EXPECT_LE((group.vee(chain.dg(y, group.hat(u), y)) - exact * u).norm(), 1e-14 * exact.norm());
    }
}

// Link i touches links i - 1 and i + 1 only, and every neighbour's block is there.
TEST(Chain, DifferentialIsBlockTridiagonal) {
  const Chain chain{ChainParams{}};
  const int k = 6;
  const Group group(k);
  const Group::Operator m = chain.dg_matrix(group, shaken(chain, k, 3));
  Eigen::MatrixXd block_norms = Eigen::MatrixXd::Zero(k, k);
  for (int c = 0; c < m.outerSize(); ++c)
    for (Group::Operator::InnerIterator it(m, c); it; ++it) {
      EXPECT_LE(std::abs(it.row() / 12 - it.col() / 12), 1) << it.row() << ", " << it.col();
      block_norms(it.row() / 12, it.col() / 12) += it.value() * it.value();
    }
  for (int i = 0; i < k; ++i) {
    EXPECT_GT(block_norms(i, i), 0.0) << i;
    if (i > 0) {
      EXPECT_GT(block_norms(i, i - 1), 0.0) << i;
    }
    if (i + 1 < k) {
      EXPECT_GT(block_norms(i, i + 1), 0.0) << i;
    }
  }
}

// dE/dt along the field (central differences of E(y exp(t g(y))), Richardson-extrapolated) is -c sum |d_j'|^2: 0
// at c = 0.
TEST(Chain, EnergyChangesOnlyByTheDampersWork) {
  for (double c : {0.0, 200.0, 5e3}) {
    ChainParams params;
    params.damping = c;
    const Chain chain{params};
    for (int k : {2, 5}) {
      const Group group(k);
      const Element y = shaken(chain, k, 4);
      const Eigen::VectorXd g = chain.coordinates(y);
      const auto rate = [&](double t) {
        return (chain.energy(group.times_exp(y, t * g)) - chain.energy(group.times_exp(y, -t * g))) / (2 * t);
      };
      const double t = 1e-5, measured = (4 * rate(t / 2) - rate(t)) / 3;
      double dissipation = 0.0, scale = 0.0;  // scale: the springs' power, the largest term in dE/dt
      for (int j = 0; j < k; ++j) {
        dissipation += c * chain.gap_rate(y, j).squaredNorm();
        scale += params.stiffness * chain.gap(y, j).norm() * chain.gap_rate(y, j).norm();
      }
      EXPECT_NEAR(measured, -dissipation, 1e-7 * scale) << "c " << c << " k " << k;
      if (c > 0.0) {
        EXPECT_GT(dissipation, 1e-3 * scale) << "the check must see the dampers";
      }
    }
  }
}

// Hanging straight down along -z at rest, joint j (0-based) stretched by the weight of the k - j links below it
// over k_s (gamma along -z).
Element sagging(const Chain& chain, int k) {
  const ChainParams& params = chain.params();
  ChainParams straight = params;
  straight.tilt = 0.0;
  Element y = Chain{straight}.start_strip(k);
  const double weight = params.mass * -params.gravity.z();
  double top = 0.0;  // z of link i's top point
  for (int i = 0; i < k; ++i) {
    top -= (k - i) * weight / params.stiffness;
    Group::body(y, i)(2, 3) = top - params.length / 2;
    top -= params.length;
  }
  return y;
}

// At the static sag every acceleration vanishes; without it (joints closed) gravity's pull is not balanced.
TEST(Chain, HangingChainAtItsStaticSagIsAnEquilibrium) {
  ChainParams params;
  params.tilt = 0.0;
  const Chain chain{params};
  const double weight = params.mass * -params.gravity.z();
  for (int k : {2, 5}) {
    const Element y = sagging(chain, k);
    const auto accelerations = [&](const Element& state) {
      const Eigen::VectorXd g = chain.coordinates(state);
      double out = 0.0;
      for (int i = 0; i < k; ++i) out = std::max(out, g.segment<6>(12 * i + 6).cwiseAbs().maxCoeff());
      return out;
    };
    EXPECT_LT(accelerations(y), 1e-12 * k * weight) << "k " << k;
    EXPECT_GT(accelerations(chain.start_strip(k)), 0.5 * weight) << "k " << k;
  }
}

// Chain::rate bounds the rates of the linearisation at the hanging rest (dg's eigenvalues there, g = 0) and is
// within a factor 8 of the fastest, damped or not (the bound is for long chains: 5 times one link's).
TEST(Chain, RateBoundsTheModesAtRest) {
  for (double c : {0.0, 200.0, 2e3})
    for (int k : {1, 2, 4, 8}) {
      ChainParams params;
      params.damping = c;
      const Chain chain{params};
      const Eigen::MatrixXd m(chain.dg_matrix(Group(k), sagging(chain, k)));
      const double fastest = eigenvalues_of(m).cwiseAbs().maxCoeff();
      EXPECT_LE(fastest, chain.rate()) << "c " << c << " k " << k;
      EXPECT_GE(fastest, chain.rate() / 8) << "c " << c << " k " << k;
    }
}

// The start: straight, at rest, joints closed, link 1's axis turned by tilt about x from -z; the energy is
// gravity's alone.
TEST(Chain, StartsStraightAtRestWithClosedJoints) {
  const ChainParams params;
  const Chain chain{params};
  const int k = 4;
  const Element y = chain.start_strip(k);
  double potential = 0.0;
  for (int i = 0; i < k; ++i) {
    EXPECT_LE(chain.gap(y, i).norm(), 1e-15) << i;
    EXPECT_TRUE((Group::body(y, i).block<6, 1>(4, 10).isZero(0.0))) << i;
    potential -= params.mass * params.gravity.dot(Group::body(y, i).block<3, 1>(0, 3));
  }
  const Eigen::Vector3d axis = Group::body(y, 0).topLeftCorner<3, 3>() * Eigen::Vector3d::UnitZ();
  EXPECT_NEAR(std::acos(axis.dot(Eigen::Vector3d::UnitZ())), params.tilt, 1e-14);
  EXPECT_NEAR(chain.energy(y), potential, 1e-12 * std::abs(potential));
  EXPECT_LE(Group(k).defect(y), 1e-15);
}

// The reference's equations in flat coordinates (chain_flat_reference.hpp, written apart from chain.cpp) are the
// field's: the same rates of R and x, the same accelerations, at shaken states, stiff or soft.
TEST(Chain, FlatReferenceHasTheSameEquations) {
  ChainParams soft;
  soft.stiffness = 1e3;
  soft.damping = 20.0;
  for (const ChainParams& params : {ChainParams{}, soft})
    for (int k : {2, 5}) {
      const Chain chain{params};
      const test::FlatChain flat(params, k);
      const Element y = shaken(chain, k, 5);
      const Eigen::VectorXd g = chain.coordinates(y), d = flat.derivative(flat.flat(y));
      for (int i = 0; i < k; ++i) {
        const Eigen::Matrix3d r = Group::body(y, i).topLeftCorner<3, 3>();
        const Eigen::Matrix3d turn = Eigen::Map<const Eigen::Matrix3d>(d.data() + 18 * i);
        EXPECT_LE((turn - r * so3::hat(g.segment<3>(12 * i))).norm(), 1e-15) << i;
        EXPECT_LE((d.segment<3>(18 * i + 9) - r * g.segment<3>(12 * i + 3)).norm(), 1e-15) << i;
        const Eigen::Matrix<double, 6, 1> a = g.segment<6>(12 * i + 6);
        EXPECT_LE((d.segment<6>(18 * i + 12) - a).norm(), 1e-13 * a.norm()) << "link " << i << " k " << k;
      }
    }
}

// The reference's RK4 is of order 4 on the soft chain (k_s = 1e3, c = 20: its fastest rate ~125 1/s, h rate <= 0.05)
// and its 20000 steps to t = 1 are within ~1e-12 of the solution (a fifteenth of the last halving's change).
TEST(Chain, FlatReferenceConvergesAtOrderFour) {
  ChainParams soft;
  soft.stiffness = 1e3;
  soft.damping = 20.0;
  for (int k : {2, 4, 8}) {
    const test::FlatChain flat(soft, k);
    const Eigen::VectorXd s0 = flat.flat(Chain{soft}.start_strip(k));
    std::vector<Eigen::VectorXd> s;
    for (int steps : {2500, 5000, 10000, 20000}) s.push_back(flat.rk4(s0, 1.0, steps));
    const double e0 = (s[1] - s[0]).norm(), e1 = (s[2] - s[1]).norm(), e2 = (s[3] - s[2]).norm();
    EXPECT_NEAR(e0 / e1, 16.0, 2.0) << "k " << k;
    EXPECT_LT(e2, 2e-11) << "k " << k;
  }
}

// Written on the strips of (SE(3) x R^6)^k alone: not on one link's group, nor on k attitudes, nor SO(n).
TEST(Chain, IsDefinedOnTheLinksPowerGroupOnly) {
  EXPECT_TRUE(defined_on(ProblemKind::chain, SE3xR6PowerGroup(2)));
  EXPECT_TRUE(defined_on(ProblemKind::chain, SE3xR6PowerGroup(128)));
  EXPECT_FALSE(defined_on(ProblemKind::chain, SE3xR6Group{}));
  EXPECT_FALSE(defined_on(ProblemKind::chain, SO3xR3PowerGroup(4)));
  EXPECT_FALSE(defined_on(ProblemKind::chain, SO3xR3Group{}));
  EXPECT_FALSE(defined_on(ProblemKind::chain, SONGroup(11)));
  EXPECT_EQ(required_group(ProblemKind::chain), std::optional<std::string>("SExR^k"));
  EXPECT_EQ(required_index(ProblemKind::chain), std::nullopt);  // n = k, any the family takes
  EXPECT_TRUE(starts_from_parameters(ProblemKind::chain));
}

// Each parameter out of its domain is a 422 naming it; a z beside the tilt that gives the start too.
TEST(Chain, BadParametersAre422NamingTheField) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Spoiled {
    const char* field;
    std::function<void(ProblemSpec&)> spoil;
  };
  const std::vector<Spoiled> cases = {
      {"chain.mass", [](ProblemSpec& p) { p.chain.mass = 0.0; }},
      {"chain.mass", [&](ProblemSpec& p) { p.chain.mass = nan; }},
      {"chain.length", [](ProblemSpec& p) { p.chain.length = -0.5; }},
      {"chain.length", [](ProblemSpec& p) { p.chain.length = 2 * ChainParams::kBound; }},
      {"chain.stiffness", [](ProblemSpec& p) { p.chain.stiffness = -1.0; }},
      {"chain.stiffness", [](ProblemSpec& p) { p.chain.stiffness = std::numeric_limits<double>::infinity(); }},
      {"chain.damping", [](ProblemSpec& p) { p.chain.damping = -1e-3; }},
      {"chain.damping", [&](ProblemSpec& p) { p.chain.damping = nan; }},
      {"chain.inertia", [](ProblemSpec& p) { p.chain.inertia.z() = 0.0; }},
      {"chain.gravity", [&](ProblemSpec& p) { p.chain.gravity.x() = nan; }},
      {"chain.gravity", [](ProblemSpec& p) { p.chain.gravity.z() = -1e300; }},
      {"chain.tilt", [](ProblemSpec& p) { p.chain.tilt = 4.0; }},
      {"chain.tilt", [&](ProblemSpec& p) { p.chain.tilt = nan; }},
      {"z", [](ProblemSpec& p) { p.z = Eigen::MatrixXd::Identity(22, 22); }},
  };
  ProblemSpec valid;
  valid.kind = ProblemKind::chain;
  valid.group = "SExR^k";
  valid.n = 2;
  EXPECT_NO_THROW(validation::check_chain(valid));
  valid.chain.stiffness = valid.chain.damping = 0.0;  // free links, undamped: allowed
  EXPECT_NO_THROW(validation::check_chain(valid));
  for (const Spoiled& c : cases) {
    ProblemSpec spoiled = valid;
    c.spoil(spoiled);
    try {
      validation::check_chain(spoiled);
      ADD_FAILURE() << c.field << " was accepted";
    } catch (const RequestError& e) {
      EXPECT_EQ(e.kind(), RequestError::Kind::unprocessable) << c.field << ": " << e.what();
      EXPECT_EQ(e.field(), c.field) << e.what();
    }
  }
}

}  // namespace
}  // namespace lienewton
