#include "validation.hpp"

#include <cmath>

namespace lienewton::validation {

void check_n(const std::string& field, int n) {
  if (n < 2 || n > kMaxN) invalid(field, field + " must be an integer in [2, " + std::to_string(kMaxN) + "]");
}

void check_h(const std::string& field, double h) {
  if (!std::isfinite(h) || h <= 0.0 || h > kMaxH) invalid(field, field + " must be a finite number in (0, 1e6]");
}

void check_tol(double tol) {
  if (!std::isfinite(tol) || tol < 1e-16 || tol > 1.0) invalid("tol", "tol must be a finite number in [1e-16, 1]");
}

void check_max_iterations(int max_iterations) {
  if (max_iterations < 1 || max_iterations > kMaxIterationsLimit)
    invalid("max_iterations", "max_iterations must be an integer in [1, " + std::to_string(kMaxIterationsLimit) + "]");
}

void check_problem_dimension(ProblemKind problem, int n, const std::string& field) {
  if (problem == ProblemKind::rigid_body && n != 3)
    unprocessable(field, "rigid-body is a problem on SO(3): n must be 3, got " + std::to_string(n));
}

void check_rigid_body(const RigidBodyParams& p) {
  if (!p.inertia.allFinite() || (p.inertia.array() <= 0.0).any())
    invalid("rigid_body.inertia", "rigid_body.inertia must be three finite positive numbers");
  if (!p.momentum.allFinite()) invalid("rigid_body.momentum", "rigid_body.momentum must be three finite numbers");
}

void check_start_point(const std::optional<Eigen::MatrixXd>& z, int n) {
  if (!z) return;
  if (z->rows() != n || z->cols() != n) invalid("z", "z must be an n x n array of rows");
  if (!z->allFinite()) invalid("z", "z must have finite entries");
  const double orth = (z->transpose() * *z - Eigen::MatrixXd::Identity(n, n)).norm();
  if (!(orth <= 1e-10)) unprocessable("z", "z must be orthogonal to 1e-10 (||z^T z - I||_F = " + std::to_string(orth) + ")");
}

}  // namespace lienewton::validation
