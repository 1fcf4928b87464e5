// The oracle of residual_oracle.hpp.
#include "residual_oracle.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <unsupported/Eigen/MatrixFunctions>

namespace lienewton {

Eigen::MatrixXd oracle_g(ProblemKind problem, const Eigen::MatrixXd& y) {
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

Eigen::MatrixXd oracle_log(const Eigen::MatrixXd& a) { return a.log(); }
Eigen::MatrixXd oracle_exp(const Eigen::MatrixXd& a) { return a.exp(); }

Oracle oracle(ProblemKind problem, double h, const Eigen::MatrixXd& z, const Eigen::MatrixXd& y) {
  const Eigen::MatrixXd w = h * oracle_g(problem, y);
  const Eigen::MatrixXd zty = z.transpose() * y;
  const Eigen::MatrixXd log_zty = oracle_log(zty);
  Oracle o;
  o.residual = (log_zty - w).norm() / std::sqrt(2.0);
  o.defect = (y - z * oracle_exp(w)).norm();
  o.angle = Eigen::JacobiSVD<Eigen::MatrixXd>(w).singularValues()(0);
  return o;
}

}  // namespace lienewton
