// libFuzzer harness over the user-program language (core/user_field): any byte string, read as a program g for
// n = 1..6 (the first byte), must compile or throw RequestError naming g with a position -- never crash, hang or
// hit UB -- and a program that compiles must evaluate with its tangent, and with the tangents of two directions in
// one pass (dg_y's matrix), to matrices of the right size.
#include <Eigen/Dense>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "core/request_error.hpp"
#include "core/user_field/program.hpp"

using namespace lienewton;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const int n = 1 + data[0] % 6;
  const std::string_view source(reinterpret_cast<const char*>(data + 1), size - 1);
  const user_field::Parameters parameters{{"J", Eigen::MatrixXd::Identity(3, 3)}, {"c", Eigen::MatrixXd::Ones(1, 1)}};
  std::shared_ptr<const user_field::Program> program;
  try {
    program = user_field::compile(source, n, parameters);
  } catch (const RequestError& e) {
    if (e.field() != "g" || e.line() < 1 || e.column() < 1) std::abort();
    return 0;
  }
  const Eigen::MatrixXd y = Eigen::MatrixXd::Identity(n, n) + 0.1 * Eigen::MatrixXd::Ones(n, n);
  Eigen::MatrixXd g, dg;
  program->eval_with_tangent(y, 0.5, Eigen::MatrixXd::Ones(n, n), g, dg);
  if (g.rows() != n || g.cols() != n || dg.rows() != n || dg.cols() != n) std::abort();
  Eigen::MatrixXd us(2 * n, n), dgs;
  us << Eigen::MatrixXd::Ones(n, n), Eigen::MatrixXd::Identity(n, n);
  program->eval_along(y, 0.5, us, dgs);
  if (dgs.rows() != 2 * n || dgs.cols() != n) std::abort();
  return 0;
}
