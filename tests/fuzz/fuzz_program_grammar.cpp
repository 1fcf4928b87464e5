// libFuzzer harness over the user-program language that writes programs from its grammar: the input's bytes are
// read, one choice at a time (FuzzedDataProvider), as a derivation -- a few assignments of expressions built from
// the language's operators, calls and indexing over empty (0x0, 0xk, kx0), scalar, vector, non-square, t- and
// y-dependent operands, then g as one of a few forms that reach the right size from any operand (norm, trace,
// a - a', a scalar entry). libFuzzer's byte mutations then change whole productions, not characters, so nearly
// every input is a well-formed program and most compile: the compiler's folding, the evaluator, the stacked
// tangents and a Newton step see operands of every shape. Each program then goes through parse, compile (with
// constant folding), g(y), its tangent, dg_y's matrix of two directions (eval_along) and a solve of one Newton
// iteration on SO(n) -- which must throw RequestError naming g (or parameters) with a position, or finish.
#include <fuzzer/FuzzedDataProvider.h>

#include <Eigen/Dense>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "core/request_error.hpp"
#include "core/solve.hpp"
#include "program_checks.hpp"

using namespace lienewton;

namespace {

class Writer {
 public:
  explicit Writer(FuzzedDataProvider& in) : in_(in) {}

  std::string program() {
    std::string out;
    const int assignments = in_.ConsumeIntegralInRange(1, 4);
    for (int i = 0; i < assignments; ++i) out += "a" + std::to_string(i) + " = " + expression(4) + ";\n";
    const std::string a = "a" + std::to_string(in_.ConsumeIntegralInRange(0, assignments - 1));
    switch (in_.ConsumeIntegralInRange(0, 6)) {
      case 0: return out + "g = " + expression(4);
      case 1: return out + "g = (y - y')*norm(" + a + ")";
      case 2: return out + "g = " + a + " - " + a + "'";
      case 3: return out + "g = skew(y*trace(" + a + "))";
      case 4: return out + "g = (y - y')*" + a + "(1)";
      case 5: return out + "g = skew(y*" + a + ")";
      default: return out + "g = skew(" + a + "*y)";
    }
  }

 private:
  std::string pick(std::initializer_list<const char*> options) {
    const auto k = in_.ConsumeIntegralInRange<std::size_t>(0, options.size() - 1);
    return *(options.begin() + static_cast<std::ptrdiff_t>(k));
  }

  std::string operand() {
    switch (in_.ConsumeIntegralInRange(0, 9)) {
      case 0: return pick({"y", "y'", "t", "pi", "J", "c", "v", "w", "E"});
      case 1: return pick({"zeros(0)", "zeros(0,3)", "zeros(3,0)", "ones(0,1)", "eye(0)", "[]", "[[] []]"});
      case 2: return pick({"y(:,[])", "y([],:)", "y([],[])", "y(1,:)", "y(:,end)", "y(end)", "y(:)", "y(1:end-1,:)"});
      case 3: return pick({"ones(2,3)", "eye(3)", "ones(1,3)", "1:3", "(1:3)'", "3:-1:1", "1:0", "eye(2,4)"});
      case 4: return pick({"0", "1", "-1", "2", "0.5", "1e308", "1e-308", "3"});
      case 5: return pick({"size(y)", "size(y,1)", "size(y,2)", "n1"});
      case 6: return "a0";
      default: return pick({"y", "t", "c", "J"});
    }
  }

  std::string expression(int depth) {
    if (depth <= 0) return operand();
    switch (in_.ConsumeIntegralInRange(0, 11)) {
      case 0: case 1:
        return "(" + expression(depth - 1) + " " + pick({"+", "-", "*", ".*", "./", "/", "\\", ".^", "^"}) + " " +
               expression(depth - 1) + ")";
      case 2:
        return pick({"sin", "cos", "tan", "exp", "log", "sqrt", "abs", "tanh", "sinh", "cosh", "norm", "inv", "trace",
                     "skew", "transpose", "diag", "triu", "tril"}) +
               "(" + expression(depth - 1) + ")";
      case 3:
        return pick({"diag", "triu", "tril"}) + "(" + expression(depth - 1) + ", " + pick({"0", "1", "-1", "-5", "4"}) + ")";
      case 4: return "cross(" + expression(depth - 1) + ", " + expression(depth - 1) + ")";
      case 5:
        return "[" + expression(depth - 1) + pick({", ", " ", "; "}) + expression(depth - 1) + "]";
      case 6: return expression(depth - 1) + pick({"'", ".'", "^2", "^-1", "^3", "^0", ".^2"});
      case 7: return pick({"-", "+"}) + expression(depth - 1);
      case 8:
        return pick({"y", "J", "w", "a0", "E", "v"}) + "(" + index() + (in_.ConsumeBool() ? ", " + index() : "") + ")";
      case 9: return pick({"zeros", "ones", "eye"}) + "(" + shape() + ")";
      default: return operand();
    }
  }

  std::string index() {
    return pick({":", "1", "end", "[]", "1:end", "end:-1:1", "[1 1]", "1:0", "2", "[1;2]", "1/0", "0", "end+1",
                 "0.5", "size(y,1)", "(1:end)'"});
  }
  std::string shape() {
    return pick({"0", "1", "2", "3", "0, 3", "3, 0", "0, 0", "2, 3", "size(y)", "size(y,1)", "n1, 2", "1, 0"});
  }

  FuzzedDataProvider& in_;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  const int n = in.ConsumeIntegralInRange(1, 4);
  const std::string source = Writer(in).program();
  const user_field::Parameters parameters{{"J", Eigen::MatrixXd::Identity(3, 3)},
                                          {"c", Eigen::MatrixXd::Ones(1, 1)},
                                          {"n1", Eigen::MatrixXd::Constant(1, 1, 2.0)},
                                          {"v", Eigen::MatrixXd::Ones(1, 3)},
                                          {"w", Eigen::MatrixXd::Ones(2, 3)},
                                          {"E", Eigen::MatrixXd(0, 0)}};
  if (!fuzz::check_program(source, n, parameters)) return 0;
  // One Newton iteration on SO(n) (n >= 2), through the request's own validation.
  if (n < 2) return 0;
  SolveRequest request;
  request.problem.n = n;
  request.problem.g = source;
  request.problem.parameters = parameters;
  request.solver.max_iterations = 1;
  try {
    (void)solve(request);
  } catch (const RequestError& e) {
    if (e.field() != "g") std::abort();
  }
  return 0;
}
