#pragma once
// An independent judge of which root an integrator's step took: natural-parameter continuation, in the step size
// tau from 0 to h, of the root of an implicit Runge-Kutta-Munthe-Kaas stage system
//   K_i = dexpinv~_{Theta_i}(g(t_i(tau), y expm(Theta_i))),  Theta_i = tau sum_j a_ij K_j,
// from K_i = g(t, y) at tau = 0. Written for the tests only and sharing nothing with the integrators: the algebra
// as matrices on a given Frobenius-orthogonal basis, ad as the commutator, expm from Eigen's MatrixFunctions
// (residual_oracle.hpp), the Jacobian and the tangent by central differences, its own predictor and acceptance.
// The truncated dexpinv is the method's definition (the series (3.9) after ad^degree, beta = 1, 1/2, B_2k/(2k)!).
// A DIRK stage, an equation of (1.1), is the case s = 1, a = 1, degree 0, its time held at the stage's own.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include "residual_oracle.hpp"

namespace lienewton::test {

using TimedField = std::function<Eigen::MatrixXd(double t, const Eigen::MatrixXd& y)>;

struct StageSystem {
  TimedField g;
  std::vector<Eigen::MatrixXd> basis;  // of the algebra, Frobenius-orthogonal
  Eigen::MatrixXd a;                   // s x s
  int degree = 0;                      // of the truncated dexpinv
  bool time_along_tau = true;          // stage i at t + c_i tau (RKMK); false: at t (a DIRK stage, t its own time)
};

struct TrackedStages {
  bool reached = false;  // followed to tau = h
  double tau = 0.0;      // the last tau reached
  Eigen::VectorXd k;     // the stacked stages' coordinates there
};

class StageTracker {
 public:
  StageTracker(const StageSystem& sys, const Eigen::MatrixXd& y, double t) : sys_(sys), y_(y), t_(t) {}

  Eigen::MatrixXd hat(const Eigen::VectorXd& c) const {
    Eigen::MatrixXd m = Eigen::MatrixXd::Zero(y_.rows(), y_.cols());
    for (std::size_t a = 0; a < sys_.basis.size(); ++a) m += c(static_cast<Eigen::Index>(a)) * sys_.basis[a];
    return m;
  }
  Eigen::VectorXd vee(const Eigen::MatrixXd& m) const {
    Eigen::VectorXd c(q());
    for (std::size_t a = 0; a < sys_.basis.size(); ++a)
      c(static_cast<Eigen::Index>(a)) = (sys_.basis[a].array() * m.array()).sum() / sys_.basis[a].squaredNorm();
    return c;
  }
  int q() const { return static_cast<int>(sys_.basis.size()); }
  int s() const { return static_cast<int>(sys_.a.rows()); }
  Eigen::VectorXd theta(const Eigen::VectorXd& k, double tau, int i) const {
    Eigen::VectorXd th = Eigen::VectorXd::Zero(q());
    for (int j = 0; j < s(); ++j) th += tau * sys_.a(i, j) * k.segment(j * q(), q());
    return th;
  }
  Eigen::VectorXd thetas(const Eigen::VectorXd& k, double tau) const {
    Eigen::VectorXd out(k.size());
    for (int i = 0; i < s(); ++i) out.segment(i * q(), q()) = theta(k, tau, i);
    return out;
  }

  Eigen::VectorXd residual(const Eigen::VectorXd& k, double tau) const {
    static const double beta[] = {1.0, 0.5, 1.0 / 12, 0.0, -1.0 / 720, 0.0, 1.0 / 30240};
    Eigen::VectorXd f(k.size());
    for (int i = 0; i < s(); ++i) {
      const Eigen::MatrixXd th = hat(theta(k, tau, i));
      const double time = sys_.time_along_tau ? t_ + sys_.a.row(i).sum() * tau : t_;
      Eigen::MatrixXd x = sys_.g(time, y_ * oracle_exp(th)), sum = x;
      for (int d = 1; d <= sys_.degree; ++d) {
        x = th * x - x * th;
        sum += beta[d] * x;
      }
      f.segment(i * q(), q()) = k.segment(i * q(), q()) - vee(sum);
    }
    return f;
  }

  Eigen::MatrixXd jacobian(const Eigen::VectorXd& k, double tau) const {
    Eigen::MatrixXd j(k.size(), k.size());
    for (Eigen::Index c = 0; c < k.size(); ++c) {
      const double d = 1e-6 * (1.0 + std::abs(k(c)));
      Eigen::VectorXd kp = k, km = k;
      kp(c) += d;
      km(c) -= d;
      j.col(c) = (residual(kp, tau) - residual(km, tau)) / (kp(c) - km(c));
    }
    return j;
  }

  // dK/dtau = -(D_K F)^-1 dF/dtau.
  Eigen::VectorXd tangent(const Eigen::VectorXd& k, double tau, const Eigen::MatrixXd& jac) const {
    const double d = 1e-6 * std::max(tau, 1e-6);
    const double below = std::max(0.0, tau - d);
    const Eigen::VectorXd ft = (residual(k, tau + d) - residual(k, below)) / (tau + d - below);
    return -jac.partialPivLu().solve(ft);
  }

  // Newton from x at tau with jac, refreshed when a correction does not halve. Converged when a correction is at
  // the rounding level of x, or stops shrinking there (a stiff field's residual carries k times eps).
  bool correct(double tau, Eigen::MatrixXd jac, Eigen::VectorXd& x) const {
    Eigen::PartialPivLU<Eigen::MatrixXd> lu(jac);
    bool refreshed = false;
    double last = std::numeric_limits<double>::infinity();
    for (int it = 0; it < 30; ++it) {
      const Eigen::VectorXd f = residual(x, tau);
      if (!f.allFinite()) return false;
      Eigen::VectorXd dx = -lu.solve(f);
      const double scale = 1.0 + x.norm();
      if (dx.norm() <= 1e-13 * scale) return true;
      if (dx.norm() > 0.5 * last) {
        if (last <= 1e-9 * scale) return true;
        if (refreshed) return false;
        refreshed = true;
        lu.compute(jacobian(x, tau));
        dx = -lu.solve(f);
        last = std::numeric_limits<double>::infinity();
      }
      last = dx.norm();
      x += dx;
    }
    return false;
  }

  // The stages of the stage points Theta at tau > 0: K = (A^-1 (x) I) Theta / tau.
  Eigen::VectorXd stages_of(const Eigen::VectorXd& theta, double tau) const {
    const Eigen::MatrixXd inverse = sys_.a.inverse();
    Eigen::VectorXd k = Eigen::VectorXd::Zero(theta.size());
    for (int i = 0; i < s(); ++i)
      for (int j = 0; j < s(); ++j) k.segment(i * q(), q()) += inverse(i, j) / tau * theta.segment(j * q(), q());
    return k;
  }

  // From K_i = g(t, y) at tau = 0 to h: the prediction is made in Theta (bounded and smooth in tau, where K may
  // grow like 1/tau across a stiff layer), each step's Theta moves by at most 1/2 along the tangent and its corrected
  // root may lie at most min(0.1, dtau (0.1 |dTheta/dtau| + 0.01)) from the prediction, so it never jumps roots.
  TrackedStages track(double h) const {
    Eigen::VectorXd k(s() * q());
    const Eigen::VectorXd g0 = vee(sys_.g(t_, y_));
    for (int i = 0; i < s(); ++i) k.segment(i * q(), q()) = g0;
    double tau = 0.0, step = std::min(h, 1.0 / 64);
    Eigen::MatrixXd jac = jacobian(k, tau);
    Eigen::VectorXd dk = tangent(k, tau, jac);
    for (int tries = 0; tau < h && tries < 20000; ++tries) {
      const Eigen::VectorXd dtheta = thetas(k + tau * dk, 1.0);  // d Theta / d tau = A (K + tau dK/dtau)
      const double speed = dtheta.norm();
      if (step * speed > 0.5) step = 0.5 / speed;
      double next = tau + step;
      if (next > h - 1e-3 * step) next = h;
      const double dtau = next - tau;
      const Eigen::VectorXd predicted = thetas(k, tau) + dtau * dtheta;
      Eigen::VectorXd x = stages_of(predicted, next);
      const bool converged = correct(next, jac, x);
      const double allowed = std::min(0.1, dtau * (0.1 * speed + 0.01));
      const double off = (thetas(x, next) - predicted).norm();
      if (converged && off <= allowed) {
        k = x;
        tau = next;
        jac = jacobian(k, tau);
        dk = tangent(k, tau, jac);
        step = dtau * std::clamp(0.25 * allowed / std::max(off, 1e-300), 0.5, 2.0);
        continue;
      }
      step = 0.5 * dtau;
      if (step < 1e-12 * std::max(tau, 1e-6)) break;
    }
    return {tau == h, tau, k};
  }

  // y expm(h sum_j b_j K_j).
  Eigen::MatrixXd next(const Eigen::VectorXd& k, double h, const Eigen::VectorXd& b) const {
    Eigen::VectorXd u = Eigen::VectorXd::Zero(q());
    for (int j = 0; j < s(); ++j) u += h * b(j) * k.segment(j * q(), q());
    return y_ * oracle_exp(hat(u));
  }

 private:
  const StageSystem& sys_;
  Eigen::MatrixXd y_;
  double t_;
};

}  // namespace lienewton::test
