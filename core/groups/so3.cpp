#include "so3.hpp"

#include <Eigen/LU>  // determinant
#include <array>
#include <limits>

#include "bernoulli.hpp"
#include "log_domain.hpp"

namespace lienewton::so3 {
namespace {

constexpr double kSeriesLimit = 2.0;    // below: power series for C and D (cancellation, see so3.hpp)
constexpr double kUnderflowLimit = 1e-4;  // below: Taylor polynomials for A and B (t^2 underflow)

// (t - sin t)/t^3 = sum_k (-1)^k t^2k / (2k+3)!
constexpr std::array<double, 12> kCSeries = {
    1.0 / 6,          -1.0 / 120,        1.0 / 5040,        -1.0 / 362880,     1.0 / 39916800,   -1.0 / 6227020800,
    1.0 / 1307674368000, -1.0 / 355687428096000, 1.0 / 1.21645100408832e17, -1.0 / 5.109094217170944e19,
    1.0 / 2.585201673888498e22, -1.0 / 1.5511210043330986e25};

// (1 - (t/2)cot(t/2))/t^2 = sum_k |B_2k|/(2k)! t^(2k-2), k = 1..18
constexpr const std::array<double, 18>& kDSeries = kBernoulliOverFactorial;

template <std::size_t K>
double horner_in_t2(const std::array<double, K>& c, double t2) {
  double acc = c[K - 1];
  for (std::size_t k = K - 1; k-- > 0;) acc = acc * t2 + c[k];
  return acc;
}

}  // namespace

double one_minus_cos_over_t2(double t) {
  if (t < kUnderflowLimit) return 0.5 - t * t / 24.0;
  const double s = std::sin(0.5 * t) / t;
  return 2.0 * s * s;
}

Rodrigues rodrigues(double t) {
  if (t < kUnderflowLimit) return {1.0 - t * t / 6.0, one_minus_cos_over_t2(t)};
  const double s = std::sin(0.5 * t), c = std::cos(0.5 * t);  // sin t = 2 s c, 1 - cos t = 2 s^2
  const double s_over_t = s / t;
  return {2.0 * s_over_t * c, 2.0 * s_over_t * s_over_t};
}

double t_minus_sin_over_t3(double t) {
  if (t < kSeriesLimit) return horner_in_t2(kCSeries, t * t);
  return (t - std::sin(t)) / (t * t * t);
}

double dexpinv_coefficient(double t) {
  if (t < kSeriesLimit) return horner_in_t2(kDSeries, t * t);
  return (1.0 - 0.5 * t * std::cos(0.5 * t) / std::sin(0.5 * t)) / (t * t);
}

Vec log(const Mat& r) {
  const double c = 0.5 * (r.trace() - 1.0);
  const Vec s = vee(r);  // sin(t) * axis
  const double sn = safe_norm(s);
  const double t = std::atan2(sn, c);
  if (c > -0.5) {  // t < 2pi/3: sin t >= 0.86, the antisymmetric part determines the axis well
    if (sn == 0.0) return Vec::Zero();
    return (t / sn) * s;
  }
  // Near pi: (R + R^T)/2 - c I = (1 - c) a a^T. Take the column with the largest diagonal entry.
  Mat b = 0.5 * (r + r.transpose());
  b.diagonal().array() -= c;
  Eigen::Index j = 0;
  b.diagonal().maxCoeff(&j);
  Vec axis = b.col(j) / std::sqrt(b(j, j) * (1.0 - c));
  axis.normalize();
  if (axis.dot(s) < 0.0) axis = -axis;
  return t * axis;
}

Vec checked_log(const Mat& r) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // A NaN or Inf entry makes the defect NaN or Inf and fails this test too: only then is allFinite (3 % of a
  // basin map when asked first) worth its cost, to name the cause.
  if (!((r.transpose() * r - Mat::Identity()).norm() <= 1e-8)) {
    if (!r.allFinite()) throw LogDomainError("log of a matrix with non-finite entries", nan);
    throw LogDomainError("log of a matrix that is not orthogonal", nan);
  }
  if (r.determinant() < 0.0) throw LogDomainError("log of a matrix with determinant -1 (not in SO(3))", nan);
  return log(r);
}

}  // namespace lienewton::so3
