// libFuzzer harness over the user-program language (core/user_field): any byte string, read as a program g for
// n = 1..6 (the first byte), must compile or throw RequestError naming g with a position -- never crash, hang or
// hit UB -- and a program that compiles must evaluate with its tangent, and with the tangents of two directions in
// one pass (dg_y's matrix), to matrices of the right size.
#include <Eigen/Dense>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "program_checks.hpp"

using namespace lienewton;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const int n = 1 + data[0] % 6;
  const std::string_view source(reinterpret_cast<const char*>(data + 1), size - 1);
  const user_field::Parameters parameters{{"J", Eigen::MatrixXd::Identity(3, 3)}, {"c", Eigen::MatrixXd::Ones(1, 1)}};
  fuzz::check_program(source, n, parameters);
  return 0;
}
