#pragma once
// What both program fuzzers ask of a program: it compiles, or throws RequestError naming g with a position; a
// program that compiles evaluates with its tangent, and with the tangents of two directions in one pass (dg_y's
// matrix), to matrices of the right size -- never a crash, a hang or UB. Returns whether it compiled.
#include <Eigen/Dense>
#include <cstdlib>
#include <string_view>

#include "core/request_error.hpp"
#include "core/user_field/program.hpp"

namespace lienewton::fuzz {

inline bool check_program(std::string_view source, int n, const user_field::Parameters& parameters) {
  std::shared_ptr<const user_field::Program> program;
  try {
    program = user_field::compile(source, n, parameters);
  } catch (const RequestError& e) {
    if (e.field() != "g" || e.line() < 1 || e.column() < 1) std::abort();
    return false;
  }
  const Eigen::MatrixXd y = Eigen::MatrixXd::Identity(n, n) + 0.1 * Eigen::MatrixXd::Ones(n, n);
  Eigen::MatrixXd g, dg;
  program->eval(y, 0.25, g);
  program->eval_with_tangent(y, 0.5, Eigen::MatrixXd::Ones(n, n), g, dg);
  if (g.rows() != n || g.cols() != n || dg.rows() != n || dg.cols() != n) std::abort();
  Eigen::MatrixXd dys(2 * n, n), dgs;
  dys << Eigen::MatrixXd::Ones(n, n), Eigen::MatrixXd::Identity(n, n);
  program->eval_along(y, 0.5, dys, dgs);
  if (dgs.rows() != 2 * n || dgs.cols() != n) std::abort();
  return true;
}

}  // namespace lienewton::fuzz
