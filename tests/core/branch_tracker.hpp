#pragma once
// An independent judge of "which root": natural-parameter continuation of the root of the implicit Euler
// equation y = z expm(tau g(y)) from (y = z, tau = 0) to tau = h, written for the tests only. It shares nothing
// with the solvers: its unknown is the skew matrix V of y = z expm(V) (coordinates: the upper-triangle entries,
// which are the coefficients on the basis E_ij - E_ji), its equation F(v, tau) = v - tau g(z expm(V)), its
// Jacobian central differences of F, and its exp/log Eigen's MatrixFunctions (through residual_oracle.hpp, so
// the heavy header is compiled once). Because V is not a principal logarithm, the tracker follows z's root
// past log's cut. It cannot pass a fold: there the step shrinks to nothing and the smallest singular value of
// D_v F at the last root shows why.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "residual_oracle.hpp"

namespace lienewton::test {

using MatrixField = std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)>;

struct TrackedBranch {
  bool reached = false;  // the branch was followed to tau = h
  double h_stop = 0.0;   // the last tau reached: h if reached, else where the steps shrank to nothing
  Eigen::MatrixXd y;     // z expm(V) at h_stop
  Eigen::MatrixXd v;     // V, skew, at h_stop
  double sigma_min = 1.0;  // smallest singular value of D_v F at (V, h_stop); -> 0 at a fold
  int steps = 0;           // accepted tau steps
};

namespace branch_detail {

inline int skew_dim(Eigen::Index n) { return static_cast<int>(n * (n - 1) / 2); }

inline Eigen::VectorXd skew_coords(const Eigen::MatrixXd& m) {  // of the skew part (m - m^T)/2
  const Eigen::Index n = m.rows();
  Eigen::VectorXd c(skew_dim(n));
  for (Eigen::Index i = 0, k = 0; i < n; ++i)
    for (Eigen::Index j = i + 1; j < n; ++j, ++k) c(k) = 0.5 * (m(i, j) - m(j, i));
  return c;
}

inline Eigen::MatrixXd skew_matrix(const Eigen::VectorXd& c, Eigen::Index n) {
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index i = 0, k = 0; i < n; ++i)
    for (Eigen::Index j = i + 1; j < n; ++j, ++k) {
      m(i, j) = c(k);
      m(j, i) = -c(k);
    }
  return m;
}

// The equation in coordinates, with g's coordinates at the point kept for the tangent and the tolerance.
class ImplicitEuler {
 public:
  ImplicitEuler(const MatrixField& g, const Eigen::MatrixXd& z) : g_(g), z_(z) {}
  Eigen::MatrixXd point(const Eigen::VectorXd& v) const { return z_ * oracle_exp(skew_matrix(v, z_.rows())); }
  Eigen::VectorXd field(const Eigen::VectorXd& v) const { return skew_coords(g_(point(v))); }
  Eigen::VectorXd residual(const Eigen::VectorXd& v, double tau) const { return v - tau * field(v); }
  // D_v F by central differences; the step balances truncation (d^2) against rounding (eps / d).
  Eigen::MatrixXd jacobian(const Eigen::VectorXd& v, double tau) const {
    const Eigen::Index q = v.size();
    const double d = 6e-6 * std::cbrt(1.0 + v.lpNorm<Eigen::Infinity>());
    Eigen::MatrixXd j(q, q);
    Eigen::VectorXd vp = v, vm = v;
    for (Eigen::Index k = 0; k < q; ++k) {
      vp(k) = v(k) + d;
      vm(k) = v(k) - d;
      j.col(k) = (residual(vp, tau) - residual(vm, tau)) / (vp(k) - vm(k));
      vp(k) = vm(k) = v(k);
    }
    return j;
  }

 private:
  const MatrixField& g_;
  const Eigen::MatrixXd& z_;
};

struct Root {
  Eigen::VectorXd v;
  double tau = 0.0;
  Eigen::MatrixXd jacobian;    // D_v F at the root
  Eigen::VectorXd tangent;     // dv/dtau = (D_v F)^-1 g
};

inline Root make_root(const ImplicitEuler& eq, Eigen::VectorXd v, double tau) {
  Root r{std::move(v), tau, {}, {}};
  r.jacobian = eq.jacobian(r.v, tau);
  r.tangent = r.jacobian.partialPivLu().solve(eq.field(r.v));
  return r;
}

// Newton from the predictor at tau with the root's Jacobian, refreshed once at the iterate when a correction
// does not halve. Converged when the residual is at rounding level, or, where rounding in tau g keeps the
// residual above that (large tau), when a contracting correction is at rounding level of v itself.
inline bool correct(const ImplicitEuler& eq, const Root& from, double tau, Eigen::VectorXd& x) {
  Eigen::PartialPivLU<Eigen::MatrixXd> lu(from.jacobian);
  bool refreshed = false;
  double last = std::numeric_limits<double>::infinity();
  for (int iteration = 0; iteration < 20; ++iteration) {
    const Eigen::VectorXd gx = eq.field(x);
    const Eigen::VectorXd f = x - tau * gx;
    if (!f.allFinite()) return false;
    if (f.norm() <= 1e-12 * (1.0 + x.norm() + tau * gx.norm())) return true;
    Eigen::VectorXd dx = -lu.solve(f);
    if (dx.norm() > 0.5 * last) {
      if (refreshed) return false;
      refreshed = true;
      lu.compute(eq.jacobian(x, tau));
      dx = -lu.solve(f);
      last = std::numeric_limits<double>::infinity();
    }
    last = dx.norm();
    x += dx;
    if (last <= 1e-14 * (1.0 + x.norm())) return true;
  }
  return false;
}

// Newton with the root's Jacobian while the residual falls: the root at h then has a residual at the rounding
// floor rather than at the steps' tolerance.
inline Eigen::VectorXd polish(const ImplicitEuler& eq, const Root& root) {
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(root.jacobian);
  Eigen::VectorXd x = root.v, f = eq.residual(x, root.tau);
  for (int i = 0; i < 8; ++i) {
    const Eigen::VectorXd next = x - lu.solve(f);
    const Eigen::VectorXd f_next = eq.residual(next, root.tau);
    if (!(f_next.norm() < f.norm())) break;
    x = next;
    f = f_next;
  }
  return x;
}

}  // namespace branch_detail

// Follows z's root of y = z expm(tau g(y)) from tau = 0 to tau = h (h > 0). Steps start at min(h, 1/64), grow
// on easy corrections and halve on failure; a corrected root is accepted only when it lies close to the tangent
// predictor relative to the step, so the path never jumps to another root. The tracker stops when the step
// falls below 1e-9 tau without an accepted root (a fold, or a singular point of the path).
inline TrackedBranch track_branch(const MatrixField& g, const Eigen::MatrixXd& z, double h) {
  using namespace branch_detail;
  const ImplicitEuler eq(g, z);
  Root root = make_root(eq, Eigen::VectorXd::Zero(skew_dim(z.rows())), 0.0);
  double step = std::min(h, 1.0 / 64);
  TrackedBranch out;
  for (int tries = 0; root.tau < h && tries < 100000; ++tries) {
    // Predicted change in v at most 1/2 per step, and no sliver left before h.
    const double tangent_norm = root.tangent.norm();
    if (step * tangent_norm > 0.5) step = 0.5 / tangent_norm;
    double tau = root.tau + step;
    if (tau > h - 1e-3 * step) tau = h;
    const double dtau = tau - root.tau;
    const Eigen::VectorXd predicted = root.v + dtau * root.tangent;
    Eigen::VectorXd x = predicted;
    const bool converged = correct(eq, root, tau, x);
    const double allowed = std::min(0.1, dtau * (0.1 * tangent_norm + 0.01));
    const double off = (x - predicted).norm();
    if (converged && off <= allowed) {
      root = make_root(eq, x, tau);
      ++out.steps;
      // The predictor's error grows like dtau^2 and the allowance like dtau: aim at a quarter of the allowance.
      step = dtau * std::clamp(0.25 * allowed / off, 0.5, 2.0);
      continue;
    }
    step = 0.5 * dtau;
    if (step < 1e-9 * std::max(root.tau, std::min(h, 1.0 / 64))) break;
  }
  out.reached = root.tau == h;
  out.h_stop = root.tau;
  const Eigen::VectorXd v = out.reached ? polish(eq, root) : root.v;
  out.v = skew_matrix(v, z.rows());
  out.y = eq.point(v);
  out.sigma_min = Eigen::JacobiSVD<Eigen::MatrixXd>(root.jacobian).singularValues().minCoeff();
  return out;
}

// The implicit Euler residual as the solvers define it, ||log(z^T y) - h g(y)|| in the coordinates of the basis
// E_ij - E_ji (= Frobenius / sqrt 2), with Eigen's principal matrix logarithm.
inline double implicit_euler_residual(const MatrixField& g, const Eigen::MatrixXd& z, double h,
                                      const Eigen::MatrixXd& y) {
  return (oracle_log(z.transpose() * y) - h * g(y)).norm() / std::sqrt(2.0);
}

// The same residual on SO(3) in long double (Rodrigues' logarithm), to judge whether a claimed residual near the
// rounding floor of double is true: the double y and z are taken exactly, and the skew part of log(z^T y) is used.
using Matrix3ld = Eigen::Matrix<long double, 3, 3>;
using MatrixField3ld = std::function<Matrix3ld(const Matrix3ld&)>;

inline Eigen::Matrix<long double, 3, 1> so3_log_long(const Matrix3ld& r) {
  using V3 = Eigen::Matrix<long double, 3, 1>;
  const V3 a(0.5L * (r(2, 1) - r(1, 2)), 0.5L * (r(0, 2) - r(2, 0)), 0.5L * (r(1, 0) - r(0, 1)));  // sin(t) u
  const long double c = 0.5L * (r.trace() - 1.0L), s = a.norm();
  const long double angle = std::atan2(s, c);
  if (c > -0.5L) return s > 0.0L ? V3(a * (angle / s)) : a;  // angle/s -> 1 as the angle -> 0
  // Near pi the axis comes from the symmetric part (1 - cos t) u u^T, its sign from sin(t) u.
  const Matrix3ld b = 0.5L * (r + r.transpose()) - c * Matrix3ld::Identity();
  Eigen::Index k = 0;
  b.diagonal().maxCoeff(&k);
  V3 u = b.col(k) / std::sqrt(b(k, k) * (1.0L - c));
  if (u.dot(a) < 0.0L) u = -u;
  return angle * u;
}

inline long double implicit_euler_residual_so3_long(const MatrixField3ld& g, const Eigen::Matrix3d& z, double h,
                                                    const Eigen::Matrix3d& y) {
  const Matrix3ld zl = z.cast<long double>(), yl = y.cast<long double>();
  const Eigen::Matrix<long double, 3, 1> w = so3_log_long(zl.transpose() * yl);
  const Matrix3ld gy = g(yl);
  const Eigen::Matrix<long double, 3, 1> hg(0.5L * (gy(2, 1) - gy(1, 2)), 0.5L * (gy(0, 2) - gy(2, 0)),
                                            0.5L * (gy(1, 0) - gy(0, 1)));
  return (w - static_cast<long double>(h) * hg).norm();
}

}  // namespace lienewton::test
