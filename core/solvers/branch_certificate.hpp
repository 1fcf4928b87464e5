#pragma once
// Whether a root x_b of F(., tau_b) is the one continued from a root x_a of F(., tau_a), tau_a < tau_b: a
// Krawczyk-type existence and uniqueness test over the whole segment (Krawczyk 1969; Moore, Kearfott & Cloud,
// "Introduction to Interval Analysis", 2009, ch. 8; the paper's section 4 argues Newton's convergence from the same
// two quantities, a contraction constant and a radius). With A = D_x F(c, tau_m)^-1 at the segment's middle and the
// Newton-like map
//   N_tau(x) = x - A F(x, tau),
// if for one ball B = B(c, R) around the segment's midpoint c that holds x_a and x_b, and every tau in
// [tau_a, tau_b],
//   ||I - A D_x F(x, tau)|| <= q < 1 on B     and     ||A F(c, tau)|| + q R <= R,
// then N_tau maps B into itself as a contraction, so F(., tau) has exactly one root in B for every such tau, and
// it moves continuously with tau (the uniform contraction principle): x_a's root at tau_a is carried to x_b at
// tau_b without leaving B, with no fold and no other branch between them.
// What is computed and what is estimated: both suprema over tau are taken over tau_a, the midpoint and tau_b (exact
// where F and D_x F are affine in tau, as for a stage of (1.1): a norm of an affine function is convex); the
// variation of A D_x F across B is estimated from D_x F at x_a, c and x_b (a Lipschitz constant from two
// differences, doubled: a sampled estimate, not an enclosure, as the paper's Lipschitz constants are assumed rather
// than computed). Dense, O(q^3) in the dimension q of x.
#include <Eigen/Core>
#include <array>

namespace lienewton {

struct BranchLink {
  Eigen::VectorXd x_a, x_b;  // the known root at tau_a, the candidate at tau_b
  double tau_a = 0, tau_b = 0;
  Eigen::MatrixXd d_a, d_b;  // D_x F(x_a, tau_a), D_x F(x_b, tau_b)
  // At the midpoint c = (x_a + x_b) / 2 for tau = tau_a, (tau_a + tau_b) / 2, tau_b: D_x F(c, tau) and F(c, tau).
  std::array<Eigen::MatrixXd, 3> d_mid;
  std::array<Eigen::VectorXd, 3> f_mid;
  static std::array<double, 3> taus(double tau_a, double tau_b) { return {tau_a, (tau_a + tau_b) / 2, tau_b}; }
};

struct BranchCertificate {
  bool holds = false;
  double contraction = 0;  // q at the radius tested (infinity when D_x F(c, tau_m) is singular)
  double radius = 0;       // R
};

BranchCertificate certify_link(const BranchLink& link);

}  // namespace lienewton
