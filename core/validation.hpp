#pragma once
// Field checks shared by every request type; each throws RequestError naming the field.
#include <Eigen/Dense>
#include <optional>
#include <string>

#include "fields.hpp"
#include "options.hpp"
#include "request_error.hpp"
#include "rigid_body_params.hpp"

namespace lienewton::validation {

[[noreturn]] inline void invalid(const std::string& field, const std::string& message) {
  throw RequestError(RequestError::Kind::invalid, field, message);
}
[[noreturn]] inline void unprocessable(const std::string& field, const std::string& message) {
  throw RequestError(RequestError::Kind::unprocessable, field, message);
}

// A field of the table in fields.hpp; path names it in the error (e.g. "n", "cells[2].h").
void check(const fields::NumberField& field, double x, const std::string& path);
void check(const fields::IntegerField& field, long long x, const std::string& path);
void check_problem_dimension(ProblemKind problem, int n, const std::string& field = "n");
void check_rigid_body(const RigidBodyParams& params);
void check_start_point(const std::optional<Eigen::MatrixXd>& z, int n);
// y0, the iteration's start: n x n, finite, orthogonal to 1e-10 and in the component of z (det y0 = det z), so
// that z^-1 y0 is a rotation the iteration can reach. Throws RequestError naming "y0".
void check_start_guess(const Eigen::MatrixXd& y0, const Eigen::MatrixXd& z);

}  // namespace lienewton::validation
