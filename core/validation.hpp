#pragma once
// Field checks shared by every request type; each throws RequestError naming the field.
#include <Eigen/Dense>
#include <optional>
#include <string>

#include "request_error.hpp"
#include "options.hpp"
#include "rigid_body_params.hpp"

namespace lienewton::validation {

inline constexpr int kMaxN = 100000;        // beyond any machine's memory; front ends set tighter caps
inline constexpr int kMaxIterationsLimit = 100000;
inline constexpr double kMaxH = 1e6;
inline constexpr double kMaxTEnd = 100.0;

[[noreturn]] inline void invalid(const std::string& field, const std::string& message) {
  throw RequestError(RequestError::Kind::invalid, field, message);
}
[[noreturn]] inline void unprocessable(const std::string& field, const std::string& message) {
  throw RequestError(RequestError::Kind::unprocessable, field, message);
}

void check_n(const std::string& field, int n);
void check_h(const std::string& field, double h);
void check_tol(double tol);
void check_max_iterations(int max_iterations);
void check_problem_dimension(ProblemKind problem, int n, const std::string& field = "n");
void check_rigid_body(const RigidBodyParams& params);
void check_start_point(const std::optional<Eigen::MatrixXd>& z, int n);

}  // namespace lienewton::validation
