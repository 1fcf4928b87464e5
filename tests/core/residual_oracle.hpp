#pragma once
// An independent oracle for the paper's problems: from the returned y and the given z only, f(y) = log(z^T y) -
// h g(y) (3.6) with Eigen's Schur-Parlett principal matrix logarithm (unsupported/MatrixFunctions, not the
// production log) and the (1.1) defect ||y - z expm(h g(y))||_F with Eigen's Pade matrix exponential; g is
// written again here from the paper.
#include <Eigen/Dense>
#include <cmath>
#include <unsupported/Eigen/MatrixFunctions>

#include "core/options.hpp"

namespace lienewton {

// The paper's fields (section 5), as matrices.
inline Eigen::MatrixXd oracle_g(ProblemKind problem, const Eigen::MatrixXd& y) {
  const Eigen::Index n = y.rows();
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(n, n);
  if (problem == ProblemKind::paper_linear) {
    for (Eigen::Index i = 0; i + 1 < n; ++i) {
      out(i, i + 1) = y(i, i + 1);
      out(i + 1, i) = -y(i, i + 1);
    }
    return out;
  }
  Eigen::MatrixXd s(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) s(i, j) = std::sin(y(i, j));
  const Eigen::MatrixXd u = s * (2.0 * y - 5.0 * y * y);
  return u - u.transpose();
}

struct Oracle {
  double residual;  // ||f(y)|| in the paper's coordinates: ||F||_F / sqrt(2)
  double defect;    // ||y - z expm(h g(y))||_F
  double angle;     // the largest rotation angle of h g(y) (its spectral norm)
};

inline Oracle oracle(ProblemKind problem, double h, const Eigen::MatrixXd& z, const Eigen::MatrixXd& y) {
  const Eigen::MatrixXd w = h * oracle_g(problem, y);
  const Eigen::MatrixXd zty = z.transpose() * y;
  const Eigen::MatrixXd log_zty = zty.log();
  Oracle o;
  o.residual = (log_zty - w).norm() / std::sqrt(2.0);
  o.defect = (y - z * w.exp()).norm();
  o.angle = Eigen::JacobiSVD<Eigen::MatrixXd>(w).singularValues()(0);
  return o;
}

}  // namespace lienewton
