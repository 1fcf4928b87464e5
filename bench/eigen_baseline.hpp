#pragma once
// The baseline of the benchmarks: what a typical user would write instead of lienewton. SO(N) as dynamic-size
// Eigen matrices, exp and log from Eigen's generic unsupported/Eigen/MatrixFunctions (.exp(), .log()), the
// differential of f by forward differences (paper (3.18)/(3.19)) and the Newton system solved by dense LU.
// The algorithms (fixed point (1.2), Newton Version 1 (3.5), Version 2 (3.20)), the start point, the vector
// fields and the stopping rule (tol, stagnation at the rounding floor, divergence, iteration cap) are the same
// as lienewton's, so that a ratio measures the building blocks, not a different algorithm.
// Lives in bench/ only: it is not part of the library.
#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <unsupported/Eigen/MatrixFunctions>

#include "core/options.hpp"
#include "core/problems.hpp"

namespace lienewton::baseline {

using Mat = Eigen::MatrixXd;
using Vec = Eigen::VectorXd;

// so(N) coordinates in the paper's basis E_ij - E_ji, i < j, row-major.
inline Mat hat(const Vec& a, int n) {
  Mat m = Mat::Zero(n, n);
  int k = 0;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j, ++k) m(i, j) = a(k), m(j, i) = -a(k);
  return m;
}
inline Vec vee(const Mat& m) {
  const int n = static_cast<int>(m.rows());
  Vec a(n * (n - 1) / 2);
  int k = 0;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j, ++k) a(k) = 0.5 * (m(i, j) - m(j, i));
  return a;
}

struct EigenGenericGroup {
  int n;
  int dim() const { return n * (n - 1) / 2; }
  Mat exp(const Vec& a) const { return hat(a, n).exp(); }
  Vec log(const Mat& r) const { return vee(r.log()); }
  // dexpinv_v(u) ~ (log(exp(v) exp(t u)) - v) / t, (3.12), forward difference with t = sqrt(eps) max(1, |v|).
  Vec dexpinv_fd(const Mat& exp_v, const Vec& v, const Vec& u) const {
    const double t = std::sqrt(std::numeric_limits<double>::epsilon()) * std::max(1.0, v.norm());
    return (log(exp_v * exp(t * u)) - v) / t;
  }
};

// Dense LU solve of a q x q system, as a user would: PartialPivLU on dynamic-size matrices.
inline Vec lu_solve(const Mat& d, const Vec& f) { return d.partialPivLu().solve(f); }

// The vector fields of the paper, as plain functions on matrices (reusing the problem definitions).
inline Vec field(ProblemKind kind, const Mat& y) {
  switch (kind) {
    case ProblemKind::paper_linear: return vee(PaperLinear{}.g(y));
    case ProblemKind::paper_sine: return vee(PaperSine{}.g(y));
    case ProblemKind::rigid_body: return vee(Mat(RigidBody{}.g(y)));
    case ProblemKind::heavy_top:
    case ProblemKind::stiff_body:
    case ProblemKind::chain: break;  // fields on SO(3) x R^3 and (SE(3) x R^6)^k, not on this baseline's SO(N)
  }
  return {};
}

struct Result {
  bool converged = false;
  int iterations = 0;
  double residual = 0;
  Mat y;  // final iterate
};

// lienewton's stopping rule (iteration_monitor.cpp), restated.
class Monitor {
 public:
  Monitor(double tol, int max_iterations, int q) : tol_(tol), max_(max_iterations), sqrt_q_(std::sqrt(double(q))) {}
  // true: stop. Sets the result.
  bool stop(double r, double scale, int iteration, Result& res) {
    res.iterations = iteration;
    res.residual = r;
    if (!std::isfinite(r)) return true;
    if (r <= tol_) return res.converged = true;
    if (r > 1e8) return true;
    const double floor = 64.0 * std::numeric_limits<double>::epsilon() * sqrt_q_ * scale;
    stalled_ = (r > 0.5 * best_ && best_ <= floor) ? stalled_ + 1 : 0;
    best_ = std::min(best_, r);
    return stalled_ >= 3 || iteration >= max_;
  }

 private:
  double tol_;
  int max_;
  double sqrt_q_;
  int stalled_ = 0;
  double best_ = std::numeric_limits<double>::infinity();
};

struct Problem {
  ProblemKind kind = ProblemKind::paper_linear;
  Mat z;
  double h = 0.5;
  double tol = 1e-13;
  int max_iterations = 100;
};

// f(y) = log(z^T y) - h g(y) (3.6).
inline Vec residual(const EigenGenericGroup& g, const Problem& p, const Mat& y, Vec* v_out = nullptr,
                    Vec* hg_out = nullptr) {
  const Vec v = g.log(p.z.transpose() * y);
  const Vec hg = p.h * field(p.kind, y);
  if (v_out) *v_out = v;
  if (hg_out) *hg_out = hg;
  return v - hg;
}

// Newton Version 1 (3.5) with the forward-difference differential (3.18) and dense LU.
inline Result newton_group(const Problem& p) {
  const EigenGenericGroup g{static_cast<int>(p.z.rows())};
  const int q = g.dim();
  Monitor monitor(p.tol, p.max_iterations, q);
  Result res;
  Mat y = p.z;
  Mat d(q, q);
  for (int it = 0;; ++it) {
    Vec v, hg;
    const Vec f = residual(g, p, y, &v, &hg);
    if (monitor.stop(f.norm(), 1.0 + f.norm() + v.norm() + hg.norm(), it, res)) {
      res.y = y;
      return res;
    }
    const double t = std::sqrt(std::numeric_limits<double>::epsilon()) * std::max(1.0, v.norm());
    for (int i = 0; i < q; ++i) d.col(i) = (residual(g, p, Mat(y * g.exp(t * Vec::Unit(q, i)))) - f) / t;
    const Vec u = -lu_solve(d, f);
    if (!u.allFinite()) return res;
    y = y * g.exp(u);
  }
}

// Newton Version 2 (3.20): f~(v) = v - h g(z exp v), forward differences (3.19), dense LU.
inline Result newton_algebra(const Problem& p) {
  const EigenGenericGroup g{static_cast<int>(p.z.rows())};
  const int q = g.dim();
  Monitor monitor(p.tol, p.max_iterations, q);
  Result res;
  auto ftilde = [&](const Vec& v, Vec* hg = nullptr) {
    const Vec h_g = p.h * field(p.kind, Mat(p.z * g.exp(v)));
    if (hg) *hg = h_g;
    return Vec(v - h_g);
  };
  Vec v = Vec::Zero(q);
  Mat d(q, q);
  for (int it = 0;; ++it) {
    Vec hg;
    const Vec f = ftilde(v, &hg);
    if (monitor.stop(f.norm(), 1.0 + f.norm() + v.norm() + hg.norm(), it, res)) return res;
    const double t = std::sqrt(std::numeric_limits<double>::epsilon()) * std::max(1.0, v.norm());
    for (int i = 0; i < q; ++i) d.col(i) = (ftilde(Vec(v + t * Vec::Unit(q, i))) - f) / t;
    const Vec u = -lu_solve(d, f);
    if (!u.allFinite() || v.norm() + u.norm() > 1e8) return res;
    v += u;
  }
}

// Fixed point (1.2): y_{n+1} = z exp(h g(y_n)), residual f(y_n) as for Version 1.
inline Result fixed_point(const Problem& p) {
  const EigenGenericGroup g{static_cast<int>(p.z.rows())};
  Monitor monitor(p.tol, p.max_iterations, g.dim());
  Result res;
  Mat y = p.z;
  for (int it = 0;; ++it) {
    Vec v, hg;
    const Vec f = residual(g, p, y, &v, &hg);
    if (monitor.stop(f.norm(), 1.0 + f.norm() + v.norm() + hg.norm(), it, res)) return res;
    y = p.z * g.exp(hg);
  }
}

inline Result run(Method m, const Problem& p) {
  switch (m) {
    case Method::fixed_point: return fixed_point(p);
    case Method::newton_group: return newton_group(p);
    case Method::newton_algebra: return newton_algebra(p);
  }
  return {};
}

}  // namespace lienewton::baseline
