// Spectrum (core/solvers/spectrum.hpp) against matrices whose eigenvalues are known by construction: a block-diagonal
// matrix of real eigenvalues and 2x2 rotation-scaling blocks a I + b R (eigenvalues a +- ib), conjugated by a random
// well-conditioned matrix so that J is not normal. Its answers must be those of the known eigenvalues, on either side
// of each threshold, including where ||J||_F decides alone.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <complex>
#include <vector>

#include "core/solvers/spectrum.hpp"

namespace lienewton {
namespace {

// J = S D S^-1 with D block diagonal: reals as 1x1 blocks, pairs (a, b) as [[a, -b], [b, a]].
Eigen::MatrixXd with_eigenvalues(const std::vector<double>& reals, const std::vector<std::complex<double>>& pairs) {
  const Eigen::Index n = static_cast<Eigen::Index>(reals.size() + 2 * pairs.size());
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(n, n);
  Eigen::Index i = 0;
  for (double r : reals) d(i, i) = r, ++i;
  for (const std::complex<double>& p : pairs) {
    d(i, i) = d(i + 1, i + 1) = p.real();
    d(i, i + 1) = -p.imag();
    d(i + 1, i) = p.imag();
    i += 2;
  }
  std::srand(7);
  const Eigen::MatrixXd s = Eigen::MatrixXd::Identity(n, n) + 0.2 * Eigen::MatrixXd::Random(n, n);
  return s * d * s.inverse();
}

TEST(Spectrum, DecayRateIsTheMostNegativeRealPart) {
  const Spectrum j(with_eigenvalues({-3.0, 0.5}, {{-20.0, 100.0}, {0.0, 150.0}}));
  EXPECT_NEAR(j.decay_rate(), 20.0, 1e-9);
  EXPECT_TRUE(j.decays_faster_than(19.0));
  EXPECT_FALSE(j.decays_faster_than(21.0));  // a fast rotation (Re mu = 0, |mu| = 150) is no decay
  EXPECT_GT(j.norm(), 150.0) << "||J||_F bounds every |mu|";
}

TEST(Spectrum, NoDecayIsRateZeroToRounding) {
  const Spectrum j(with_eigenvalues({1.0, 2.0}, {{0.0, 3.0}}));
  EXPECT_LE(j.decay_rate(), 1e-12);  // Re mu = 0 of the rotation, to the eigensolver's rounding
  EXPECT_FALSE(j.decays_faster_than(1e-12));
}

TEST(Spectrum, NormAnswersAloneBelowTheThreshold) {
  const Spectrum j(with_eigenvalues({-1.0}, {{-0.5, 0.5}}));
  EXPECT_FALSE(j.decays_faster_than(2.0 * j.norm()));
  EXPECT_TRUE(j.stays_regular(0.5 / j.norm()));
}

TEST(Spectrum, RegularUnlessARealPositiveEigenvalueReachesOneOverH) {
  // mu = 4 makes I - tau J singular at tau = 1/4: regular over [0, h] for h < 1/4 only.
  const Spectrum unstable(with_eigenvalues({4.0, -50.0}, {{-1.0, 30.0}}));
  EXPECT_TRUE(unstable.stays_regular(0.2));
  EXPECT_FALSE(unstable.stays_regular(0.3));
  // Only decaying and rotating components: regular at any h.
  const Spectrum stable(with_eigenvalues({-4.0, -50.0}, {{-1.0, 30.0}, {0.0, 80.0}}));
  for (double h : {0.01, 1.0, 1e6}) EXPECT_TRUE(stable.stays_regular(h)) << h;
}

}  // namespace
}  // namespace lienewton
