#pragma once
// SE(3) in closed form: T = [[R, p], [0, 1]], algebra coordinates xi = (w, r) with hat(xi) = [[hat(w), r], [0, 0]]:
// the rotation vector w first (SO(3)'s coordinates, so3.hpp), then the translation part r. The bracket is
// [(w1, r1), (w2, r2)] = (w1 x w2, w1 x r2 - w2 x r1), and ad_xi = [[W, 0], [P, W]] with W = hat(w), P = hat(r).
//
// The paper's dexp (2.10) and dexpinv (3.9) are analytic functions f of ad_xi, and ad_xi is block lower triangular
// with equal diagonal blocks, so f(ad_xi) = [[f(W), 0], [Df(W)[P], f(W)]] (the dual-number rule: the off-diagonal
// block is the Frechet derivative of f at W in the direction P). With f(W) = I - B W + C W^2 (so3::dexp_matrix)
// and f(W) = I + W/2 + D W^2 (so3::dexpinv_matrix), theta = |w| and d theta = (w . r)/theta along P:
//   Q    = Df(W)[P]  = -B P + C (W P + P W) + (w . r) (-E W + F W^2)          (dexp's block)
//   Qinv = Dfi(W)[P] = P/2 + D (W P + P W) + (w . r) H W^2                     (dexpinv's block)
// with E = B'(theta)/theta, F = C'(theta)/theta, H = D'(theta)/theta, smooth even functions. Writing the blocks
// this way (rather than Qinv = -Jinv Q Jinv) costs no products and keeps each block accurate to its own rounding.
// exp(xi) = [[exp(W), V r], [0, 1]] with V = I + B W + C W^2 (SO(3)'s left Jacobian), and log inverts it with
// V^-1 = I - W/2 + D W^2.
//
// Error analysis of the new coefficients (eps = 2^-53), the same way as so3.hpp's:
//  E = (theta sin theta - 4 sin^2(theta/2))/theta^4 and F = (3 sin theta - theta (2 + cos theta))/theta^5
//    cancel for small theta (E's direct formula loses a factor 4.6 at theta = 2, F's 13); their power series
//    alternate and lose 2.8 resp. 2.1 at theta = 2.75, where the direct formulas lose 1.7 resp. 2.3. So below
//    2.75 they are summed as series (16 terms, truncation < 2e-24), above it from the direct formulas; near pi
//    the direct formulas do not cancel at all (1.0).
//  H = (x cot x + x^2/sin^2 x - 2)/theta^4, x = theta/2, cancels by a factor 10 near pi; its series has positive
//    terms (|B_2k|, ratio (theta/2pi)^2 <= 0.33 below 3.6), so below 3.6 it is summed as a series (40 terms,
//    truncation < 2e-20 relative), above it from the direct formula.
// tests/core/se3_test.cpp checks exp, log, dexp and dexpinv against mpmath references for theta from 1e-300 to
// 1e-3, across (0, pi) and within 1e-12 of pi.
#include <Eigen/Dense>  // cross products

#include "so3.hpp"

namespace lienewton::se3 {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat4 = Eigen::Matrix4d;
using Mat6 = Eigen::Matrix<double, 6, 6>;

inline Mat4 hat(const Vec6& xi) {
  Mat4 m = Mat4::Zero();
  m.topLeftCorner<3, 3>() = so3::hat(xi.head<3>());
  m.topRightCorner<3, 1>() = xi.tail<3>();
  return m;
}
// vee of the se(3) part (the skew part of the rotation block and the translation column): exact inverse of hat on
// se(3), a projection otherwise.
inline Vec6 vee(const Mat4& m) {
  Vec6 xi;
  xi << so3::vee(m.topLeftCorner<3, 3>()), m.topRightCorner<3, 1>();
  return xi;
}
inline Vec6 bracket(const Vec6& a, const Vec6& b) {
  Vec6 c;
  c << a.head<3>().cross(b.head<3>()), a.head<3>().cross(b.tail<3>()) - b.head<3>().cross(a.tail<3>());
  return c;
}
inline Mat6 ad_matrix(const Vec6& xi) {
  Mat6 m = Mat6::Zero();
  const Eigen::Matrix3d w = so3::hat(xi.head<3>());
  m.topLeftCorner<3, 3>() = w;
  m.bottomRightCorner<3, 3>() = w;
  m.bottomLeftCorner<3, 3>() = so3::hat(xi.tail<3>());
  return m;
}

// The coefficients' derivatives over theta (see the error analysis above).
double one_minus_cos_over_t2_slope(double t);  // E = B'(t)/t
double t_minus_sin_over_t3_slope(double t);    // F = C'(t)/t
double dexpinv_coefficient_slope(double t);    // H = D'(t)/t

// exp(xi) - I, without rounding the rotation block's diagonal to 1 (so3::expm1 says why).
Mat4 expm1(const Vec6& xi);
inline Mat4 exp(const Vec6& xi) { return Mat4::Identity() + expm1(xi); }
// The principal logarithm, |w| <= pi (so3::log's branch at pi); the caller passes an element of SE(3).
Vec6 log(const Mat4& t);
// log after checking that the rotation block is a rotation (so3::checked_log) and the last row is (0, 0, 0, 1);
// throws LogDomainError.
Vec6 checked_log(const Mat4& t);

// The blocks below the diagonal of dexp's and dexpinv's matrices (Q and Qinv above).
Eigen::Matrix3d dexp_block(const Vec6& xi);
Eigen::Matrix3d dexpinv_block(const Vec6& xi);
Mat6 dexp_matrix(const Vec6& xi);     // (2.10)
Mat6 dexpinv_matrix(const Vec6& xi);  // (3.9)
Vec6 dexp(const Vec6& xi, const Vec6& u);
Vec6 dexpinv(const Vec6& xi, const Vec6& u);

}  // namespace lienewton::se3
