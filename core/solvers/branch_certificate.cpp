#include "branch_certificate.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

namespace lienewton {
namespace {

// NaN for a matrix that is not finite (a singular D_x F(c, tau_m)): every comparison with it fails.
double spectral_norm(const Eigen::MatrixXd& e) {
  if (!e.allFinite()) return std::numeric_limits<double>::quiet_NaN();
  if (e.size() == 0) return 0.0;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> s(e.transpose() * e, Eigen::EigenvaluesOnly);
  return std::sqrt(std::max(0.0, s.eigenvalues().maxCoeff()));
}

}  // namespace

BranchCertificate certify_link(const BranchLink& link) {
  BranchCertificate out;
  out.contraction = std::numeric_limits<double>::infinity();
  const Eigen::Index q = link.x_b.size();
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(q, q);
  // A at the segment's middle: for D_x F = I - tau M, sup |tau - tau_m| ||A M|| is half what A at an end gives.
  const Eigen::PartialPivLU<Eigen::MatrixXd> a(link.d_mid[1]);
  // ||I - A D_x F(x, tau)|| <= q_mid + omega ||x - c|| on B: q_mid at c, omega the Lipschitz estimate of A D_x F
  // in x (at tau_a and tau_b, where the segment's ends are).
  double q_mid = 0.0, eta = 0.0;
  for (std::size_t k = 0; k < link.d_mid.size(); ++k) {
    const double e = spectral_norm(identity - a.solve(link.d_mid[k]));
    const double f = a.solve(link.f_mid[k]).norm();
    if (!std::isfinite(e) || !std::isfinite(f)) return out;
    q_mid = std::max(q_mid, e);
    eta = std::max(eta, f);
  }
  const double half = 0.5 * (link.x_b - link.x_a).norm();
  const double spread_a = spectral_norm(a.solve(link.d_a - link.d_mid.front()));
  const double spread_b = spectral_norm(a.solve(link.d_b - link.d_mid.back()));
  if (!std::isfinite(spread_a) || !std::isfinite(spread_b)) return out;
  const double spread = std::max(spread_a, spread_b);
  const double omega = half > 0.0 ? 2.0 * spread / half : 0.0;
  const double slack = 1.0 - q_mid;
  if (!(slack > 0.0)) return out;
  // The radius where (1 - q_mid - omega R) R - eta is largest, at least the segment's half.
  out.radius = omega > 0.0 ? std::max(half, slack / (2.0 * omega)) : std::max(half, eta / slack);
  out.contraction = q_mid + omega * out.radius;
  out.holds = out.contraction < 1.0 && eta + out.contraction * out.radius <= out.radius;
  return out;
}

}  // namespace lienewton
