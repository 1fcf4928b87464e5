#include "validation.hpp"

#include <cmath>

namespace lienewton::validation {

void check(const fields::NumberField& field, double x, const std::string& path) {
  if (!field.contains(x)) invalid(path, field.message(path));
}

void check(const fields::IntegerField& field, long long x, const std::string& path) {
  if (!field.contains(x)) invalid(path, field.message(path));
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

void check_start_guess(const Eigen::MatrixXd& y0, const Eigen::MatrixXd& z) {
  const auto n = z.rows();
  if (y0.rows() != n || y0.cols() != n) invalid("y0", "y0 must be an n x n array of rows");
  if (!y0.allFinite()) invalid("y0", "y0 must have finite entries");
  const double orth = (y0.transpose() * y0 - Eigen::MatrixXd::Identity(n, n)).norm();
  if (!(orth <= 1e-10))
    unprocessable("y0", "y0 must be orthogonal to 1e-10 (||y0^T y0 - I||_F = " + std::to_string(orth) + ")");
  if (y0.determinant() * z.determinant() < 0)
    unprocessable("y0", "y0 must lie in the component of z (det y0 = det z): z^-1 y0 must be a rotation");
}

}  // namespace lienewton::validation
