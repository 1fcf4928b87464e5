#pragma once
// Restarted-free GMRES (Saad & Schultz 1986) for A x = b with A given only as a function, for the
// matrix-free Newton systems of large N: memory O(q m) for m Krylov vectors instead of the O(q^2) of a
// dense matrix. Arnoldi with modified Gram-Schmidt and Givens rotations for the small least-squares problem.
// Written here rather than taken from Eigen's unsupported IterativeSolvers because those need a sparse
// matrix type (or a wrapper mimicking one) for the operator and give no per-iteration cancellation.
#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "cancellation.hpp"

namespace lienewton {

struct GmresResult {
  int iterations = 0;
  double relative_residual = 1.0;  // ||b - A x|| / ||b|| as tracked by the recurrence
  bool converged = false;
};

// Solves A x = b from x = 0 until ||b - A x|| <= rtol ||b|| or max_iterations Arnoldi steps. Throws Cancelled
// (cancellation.hpp) before any step once the current token is cancelled: at N = 64 under ASan the 300 steps
// of one Newton system took up to a second between the solver's own checks.
template <class Apply>
GmresResult gmres(const Apply& apply, const Eigen::VectorXd& b, Eigen::VectorXd& x, double rtol, int max_iterations) {
  const Eigen::Index q = b.size();
  const double beta = b.norm();
  x = Eigen::VectorXd::Zero(q);
  GmresResult res;
  if (beta == 0.0) {
    res.converged = true;
    res.relative_residual = 0.0;
    return res;
  }
  const int m = static_cast<int>(std::min<Eigen::Index>(max_iterations, q));
  Eigen::MatrixXd basis(q, m + 1);
  Eigen::MatrixXd hess = Eigen::MatrixXd::Zero(m + 1, m);
  Eigen::VectorXd cs = Eigen::VectorXd::Zero(m), sn = Eigen::VectorXd::Zero(m);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(m + 1);
  g(0) = beta;
  basis.col(0) = b / beta;
  int k = 0;
  for (; k < m; ++k) {
    throw_if_cancelled();
    Eigen::VectorXd w = apply(Eigen::VectorXd(basis.col(k)));
    for (int i = 0; i <= k; ++i) {
      hess(i, k) = basis.col(i).dot(w);
      w -= hess(i, k) * basis.col(i);
    }
    hess(k + 1, k) = w.norm();
    for (int i = 0; i < k; ++i) {  // previous rotations
      const double t = cs(i) * hess(i, k) + sn(i) * hess(i + 1, k);
      hess(i + 1, k) = -sn(i) * hess(i, k) + cs(i) * hess(i + 1, k);
      hess(i, k) = t;
    }
    const double r = std::hypot(hess(k, k), hess(k + 1, k));
    if (r == 0.0) break;  // A is singular on the Krylov space
    cs(k) = hess(k, k) / r;
    sn(k) = hess(k + 1, k) / r;
    const double sub = hess(k + 1, k);
    hess(k, k) = r;
    hess(k + 1, k) = 0.0;
    g(k + 1) = -sn(k) * g(k);
    g(k) = cs(k) * g(k);
    res.relative_residual = std::abs(g(k + 1)) / beta;
    if (res.relative_residual <= rtol || sub == 0.0) {
      ++k;
      res.converged = true;
      break;
    }
    basis.col(k + 1) = w / sub;
  }
  res.iterations = k;
  if (k == 0) return res;
  const Eigen::VectorXd y = hess.topLeftCorner(k, k).triangularView<Eigen::Upper>().solve(g.head(k));
  x = basis.leftCols(k) * y;
  return res;
}

}  // namespace lienewton
