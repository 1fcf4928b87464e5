#pragma once
// SO(3) in closed form. Algebra coordinates are the rotation vector w (hat(w) x = w x x); the paper's basis
// E_ij - E_ji, i < j, has coordinates alpha = (-w3, w2, -w1), a signed permutation, so all norms agree:
// |w| = ||hat(w)||_F / sqrt(2). Left-trivialised differentials as in the paper:
//   dexp_w(u)    = u - 1/2 [w,u] + 1/6 [w,[w,u]] - ...                          (2.10)
//   dexpinv_w(u) = u + 1/2 [w,u] + sum_p B_2p/(2p)! ad_w^2p (u)                  (3.9)
// with [a, b] = a x b. Fixed-size Eigen types throughout: nothing here allocates.
//
// Error analysis of the coefficient functions (eps = 2^-53):
//  A(t) = sin t / t and B(t) = (1 - cos t)/t^2 = 2 sin^2(t/2) / t^2 are evaluated from sin, which has
//    relative error <= 1 ulp, so both are accurate to ~2 ulp for every t > 0; only t^2 underflow matters:
//    below t = 1e-4 the Taylor polynomials 1 - t^2/6 (+ t^4/120) and 1/2 - t^2/24 (+ t^4/720) are used, whose
//    truncation error (< t^6/5040 < 2e-28) is far below an ulp.
//  C(t) = (t - sin t)/t^3 and D(t) = (1 - (t/2) cot(t/2))/t^2 suffer cancellation: the direct formulas lose a
//    factor t/(t - sin t) ~ 6/t^2, resp. 1/(t^2 D(t)) ~ 12/t^2, i.e. up to 3 ulp at t = 2 but 600 ulp at 0.1.
//    Below t = 2 they are summed as power series, C = sum (-1)^k t^2k/(2k+3)! (12 terms, truncation
//    < 4^12/27! < 2e-21) and D = sum |B_2k|/(2k)! t^(2k-2) (18 terms, ratio < (2/2pi)^2 = 0.101 per term,
//    truncation < 1e-18 relative); Horner's rule keeps their rounding error within 2 ulp.
// tests/core/so3_test.cpp checks every coefficient against long-double references on t in [1e-12, pi - 1e-12].
#include <Eigen/Core>
#include <cmath>

namespace lienewton::so3 {

using Vec = Eigen::Vector3d;
using Mat = Eigen::Matrix3d;

inline Mat hat(const Vec& w) {
  Mat m;
  m << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return m;
}
// vee of the skew-symmetric part: exact inverse of hat on so(3), projection otherwise.
inline Vec vee(const Mat& m) {
  return 0.5 * Vec(m(2, 1) - m(1, 2), m(0, 2) - m(2, 0), m(1, 0) - m(0, 1));
}
inline Vec bracket(const Vec& a, const Vec& b) { return a.cross(b); }

// Coefficient functions (see the error analysis above).
double one_minus_cos_over_t2(double t);  // B = (1 - cos t)/t^2
double t_minus_sin_over_t3(double t);    // C = (t - sin t)/t^3
double dexpinv_coefficient(double t);    // D = (1 - (t/2) cot(t/2))/t^2
// A = sin t / t and B together from one sin/cos pair of t/2 (the compiler fuses them into one sincos): exp is
// the inner loop of every solve, and two sin calls were 11 % of a basin map.
struct Rodrigues {
  double a, b;
};
Rodrigues rodrigues(double t);

// Rodrigues: exp(hat w) = I + A hat(w) + B hat(w)^2.
inline Mat exp(const Vec& w) {
  const auto [a, b] = rodrigues(w.norm());
  const Mat k = hat(w);
  return Mat::Identity() + a * k + b * (k * k);
}

// exp(hat w) - I = A hat(w) + B hat(w)^2, without rounding its diagonal to 1: y exp(w) computed as
// y + y expm1(w) keeps the orthogonality drift of long products a random walk (a fixed rounding of the
// diagonal of exp(w) near 1 otherwise accumulates linearly, ~20x worse over 1e4 steps).
inline Mat expm1(const Vec& w) {
  const auto [a, b] = rodrigues(w.norm());
  const Mat k = hat(w);
  return a * k + b * (k * k);
}

// |v| without under- or overflow: norm() gives 0 below |v| ~ 1e-154 and inf above 1e154. stableNorm() does
// not, but was 9 % of a basin map, so it is kept for the vectors outside those bounds only.
inline double safe_norm(const Vec& v) {
  const double n2 = v.squaredNorm();
  return (n2 > 1e-280 && n2 < 1e280) ? std::sqrt(n2) : v.stableNorm();
}

// Rotation angle in [0, pi], from atan2 of the antisymmetric and symmetric parts: accurate everywhere.
inline double angle(const Mat& r) {
  const double c = 0.5 * (r.trace() - 1.0);
  return std::atan2(safe_norm(vee(r)), c);
}

// The principal logarithm: |log R| <= pi. Away from pi, w = t/sin t * vee(R - R^T)/2; near pi the axis comes
// from the symmetric part (R + R^T)/2 - cos t I = (1 - cos t) a a^T, which loses no digits there. At exactly
// pi the axis sign is taken from the largest diagonal entry, and |w| = pi. The caller must pass a rotation
// (det +1, orthogonal); checked_log validates first.
Vec log(const Mat& r);
// log after checking that r is finite, orthogonal to 1e-8 and has det +1; throws LogDomainError.
Vec checked_log(const Mat& r);

// dexp_w = I - B K + C K^2 and dexpinv_w = I + K/2 + D K^2 with K = hat(w) (2.10), (3.9).
inline Mat dexp_matrix(const Vec& w) {
  const double t = w.norm();
  const Mat k = hat(w);
  return Mat::Identity() - one_minus_cos_over_t2(t) * k + t_minus_sin_over_t3(t) * (k * k);
}
inline Mat dexpinv_matrix(const Vec& w) {
  const double t = w.norm();
  const Mat k = hat(w);
  return Mat::Identity() + 0.5 * k + dexpinv_coefficient(t) * (k * k);
}
inline Vec dexp(const Vec& w, const Vec& u) {
  const double t = w.norm();
  const Vec wu = w.cross(u);
  return u - one_minus_cos_over_t2(t) * wu + t_minus_sin_over_t3(t) * w.cross(wu);
}
inline Vec dexpinv(const Vec& w, const Vec& u) {
  const double t = w.norm();
  const Vec wu = w.cross(u);
  return u + 0.5 * wu + dexpinv_coefficient(t) * w.cross(wu);
}

}  // namespace lienewton::so3
