#include "se3.hpp"

#include <array>
#include <cmath>
#include <limits>

#include "log_domain.hpp"

namespace lienewton::se3 {
namespace {

using Mat3 = Eigen::Matrix3d;
using Vec3 = Eigen::Vector3d;

constexpr double kSlopeSeriesLimit = 2.75;  // below: series for E and F (se3.hpp's error analysis)
constexpr double kDexpinvSlopeSeriesLimit = 3.6;  // below: series for H

// E = B'(t)/t = sum_{j>=0} 2(j+1) (-1)^(j+1) / (2j+4)! t^2j (mpmath, 17 digits)
constexpr std::array<double, 16> kESeries = {
    -8.3333333333333333e-2, 5.5555555555555556e-3,  -1.4880952380952381e-4, 2.2045855379188713e-6,
    -2.0876756987868099e-8, 1.376489471727567e-10,  -6.6912682653423394e-13, 2.4990731149737962e-15,
    -7.3985717219618967e-18, 1.7793582784901147e-20, -3.5458226564114604e-23, 5.9510310317395139e-26,
    -8.5277120163815786e-29, 1.0555965360684536e-31, -1.1401172264564231e-34, 1.0838904113667718e-37};
// F = C'(t)/t = sum_{j>=0} 2(j+1) (-1)^(j+1) / (2j+5)! t^2j
constexpr std::array<double, 16> kFSeries = {
    -1.6666666666666667e-2, 7.9365079365079365e-4,  -1.6534391534391534e-5, 2.0041686708353375e-7,
    -1.6059043836821615e-9, 9.1765964781837798e-12, -3.9360401560837291e-14, 1.3153016394598928e-16,
    -3.523129391410427e-19, 7.7363403412613681e-22, -1.4183290625645841e-24, 2.2040855673109311e-27,
    -2.9405903504764064e-30, 3.4051501163498503e-33, -3.4549006862315851e-36, 3.0968297467622051e-39};
// H = D'(t)/t = sum_{j>=0} 2(j+1) |B_(2j+4)| / (2j+4)! t^2j
constexpr std::array<double, 40> kHSeries = {
    2.7777777777777778e-3,  1.3227513227513228e-4,  4.9603174603174603e-6,  1.6701405590294479e-7,
    5.2841901386874932e-9,  1.6059043836821615e-10, 4.745552414851616e-12,  1.3737699290044551e-13,
    3.9147636574045114e-15, 1.1018005656720459e-16, 3.0699822308787551e-18, 8.4832968951107219e-20,
    2.3279145310297622e-21, 6.3502668665455126e-23, 1.7234372006616607e-24, 4.6565519219675677e-26,
    1.2532382798262055e-27, 3.3612243325542161e-29, 8.9870851796623938e-31, 2.3962687049928537e-32,
    6.3733105147668191e-34, 1.6912535751998428e-35, 4.4787224134174779e-37, 1.1837985812163269e-38,
    3.1235383709103718e-40, 8.2284957272153554e-42, 2.1644677904124254e-43, 5.6857224791189515e-45,
    1.4916464117802856e-46, 3.908673621140289e-48,  1.0230812142275845e-49, 2.6750916022652646e-51,
    6.9878388806839198e-53, 1.8236778500573241e-54, 4.7552955457751948e-56, 1.2389455884010612e-57,
    3.2254604437181814e-59, 8.3910026068003467e-61, 2.1813991004349449e-62, 5.6672292013435762e-64};

template <std::size_t K>
double horner_in_t2(const std::array<double, K>& c, double t2) {
  double acc = c[K - 1];
  for (std::size_t k = K - 1; k-- > 0;) acc = acc * t2 + c[k];
  return acc;
}

// |w| for the coefficients: only theta^2 enters them, so underflow below 1e-154 only returns their limits.
double theta_of(const Vec6& xi) { return xi.head<3>().norm(); }

}  // namespace

double one_minus_cos_over_t2_slope(double t) {
  if (t < kSlopeSeriesLimit) return horner_in_t2(kESeries, t * t);
  const double s = std::sin(0.5 * t);
  return (t * std::sin(t) - 4.0 * s * s) / ((t * t) * (t * t));
}

double t_minus_sin_over_t3_slope(double t) {
  if (t < kSlopeSeriesLimit) return horner_in_t2(kFSeries, t * t);
  return (3.0 * std::sin(t) - t * (2.0 + std::cos(t))) / ((t * t) * (t * t) * t);
}

double dexpinv_coefficient_slope(double t) {
  if (t < kDexpinvSlopeSeriesLimit) return horner_in_t2(kHSeries, t * t);
  const double x = 0.5 * t, s = std::sin(x);
  return (x * std::cos(x) / s + (x * x) / (s * s) - 2.0) / ((t * t) * (t * t));
}

Mat4 expm1(const Vec6& xi) {
  const Vec3 w = xi.head<3>(), r = xi.tail<3>();
  const double t = w.norm();
  const Vec3 wr = w.cross(r);
  Mat4 m = Mat4::Zero();
  m.topLeftCorner<3, 3>() = so3::expm1(w);
  // V r = r + B w x r + C w x (w x r), V = SO(3)'s left Jacobian
  m.topRightCorner<3, 1>() = r + so3::one_minus_cos_over_t2(t) * wr + so3::t_minus_sin_over_t3(t) * w.cross(wr);
  return m;
}

Vec6 log(const Mat4& t) {
  const Vec3 w = so3::log(t.topLeftCorner<3, 3>()), p = t.topRightCorner<3, 1>();
  const Vec3 wp = w.cross(p);
  Vec6 xi;
  // r = V^-1 p = p - 1/2 w x p + D w x (w x p)
  xi << w, p - 0.5 * wp + so3::dexpinv_coefficient(so3::safe_norm(w)) * w.cross(wp);
  return xi;
}

Vec6 checked_log(const Mat4& t) {
  const Vec3 w = so3::checked_log(t.topLeftCorner<3, 3>());  // throws for a rotation block off SO(3)
  if (!t.topRightCorner<3, 1>().allFinite())
    throw LogDomainError("log of a matrix with non-finite entries", std::numeric_limits<double>::quiet_NaN());
  if (t.row(3) != Eigen::RowVector4d(0, 0, 0, 1))
    throw LogDomainError("log of a matrix whose last row is not (0, 0, 0, 1) (not in SE(3))", so3::safe_norm(w));
  return log(t);
}

Mat3 dexp_block(const Vec6& xi) {
  const Vec3 w = xi.head<3>();
  const double t = theta_of(xi);
  const Mat3 W = so3::hat(w), P = so3::hat(xi.tail<3>());
  const Mat3 sym = W * P + P * W;
  return -so3::one_minus_cos_over_t2(t) * P + so3::t_minus_sin_over_t3(t) * sym +
         w.dot(xi.tail<3>()) * (-one_minus_cos_over_t2_slope(t) * W + t_minus_sin_over_t3_slope(t) * (W * W));
}

Mat3 dexpinv_block(const Vec6& xi) {
  const Vec3 w = xi.head<3>();
  const double t = theta_of(xi);
  const Mat3 W = so3::hat(w), P = so3::hat(xi.tail<3>());
  return 0.5 * P + so3::dexpinv_coefficient(t) * (W * P + P * W) +
         (w.dot(xi.tail<3>()) * dexpinv_coefficient_slope(t)) * (W * W);
}

Mat6 dexp_matrix(const Vec6& xi) {
  const Mat3 j = so3::dexp_matrix(xi.head<3>());
  Mat6 m = Mat6::Zero();
  m.topLeftCorner<3, 3>() = j;
  m.bottomRightCorner<3, 3>() = j;
  m.bottomLeftCorner<3, 3>() = dexp_block(xi);
  return m;
}

Mat6 dexpinv_matrix(const Vec6& xi) {
  const Mat3 j = so3::dexpinv_matrix(xi.head<3>());
  Mat6 m = Mat6::Zero();
  m.topLeftCorner<3, 3>() = j;
  m.bottomRightCorner<3, 3>() = j;
  m.bottomLeftCorner<3, 3>() = dexpinv_block(xi);
  return m;
}

Vec6 dexp(const Vec6& xi, const Vec6& u) {
  const Vec3 w = xi.head<3>();
  Vec6 out;
  out << so3::dexp(w, u.head<3>()), dexp_block(xi) * u.head<3>() + so3::dexp(w, u.tail<3>());
  return out;
}

Vec6 dexpinv(const Vec6& xi, const Vec6& u) {
  const Vec3 w = xi.head<3>();
  Vec6 out;
  out << so3::dexpinv(w, u.head<3>()), dexpinv_block(xi) * u.head<3>() + so3::dexpinv(w, u.tail<3>());
  return out;
}

}  // namespace lienewton::se3
