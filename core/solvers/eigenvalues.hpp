#pragma once
// The eigenvalues of a general real matrix, compiled once (eigenvalues.cpp): Eigen's general eigensolver (a real
// Schur form by Householder reductions) is among the costliest templates to compile, and every solver and
// integrator instance on every group would otherwise compile its own copy.
#include <Eigen/Core>

namespace lienewton {

Eigen::VectorXcd eigenvalues_of(const Eigen::MatrixXd& a);

}  // namespace lienewton
