#pragma once
// An independent oracle for the paper's problems: from the returned y and the given z only, f(y) = log(z^T y) -
// h g(y) (3.6) with Eigen's Schur-Parlett principal matrix logarithm (unsupported/MatrixFunctions, not the
// production log) and the (1.1) defect ||y - z expm(h g(y))||_F with Eigen's Pade matrix exponential; g is
// written again here from the paper. Compiled once, in residual_oracle.cpp: MatrixFunctions costs minutes of
// compiler time in the sanitizer build, per file that instantiates it.
#include <Eigen/Core>

#include "core/options.hpp"

namespace lienewton {

// The paper's fields (section 5), as matrices.
Eigen::MatrixXd oracle_g(ProblemKind problem, const Eigen::MatrixXd& y);

// Eigen's principal matrix logarithm (Schur-Parlett) and exponential (Pade), not the production ones.
Eigen::MatrixXd oracle_log(const Eigen::MatrixXd& a);
Eigen::MatrixXd oracle_exp(const Eigen::MatrixXd& a);

struct Oracle {
  double residual;  // ||f(y)|| in the paper's coordinates: ||F||_F / sqrt(2)
  double defect;    // ||y - z expm(h g(y))||_F
  double angle;     // the largest rotation angle of h g(y) (its spectral norm)
};

Oracle oracle(ProblemKind problem, double h, const Eigen::MatrixXd& z, const Eigen::MatrixXd& y);

}  // namespace lienewton
