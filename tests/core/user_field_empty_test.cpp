// Empty operands (0x0, 0xk, kx0) in a user's program, and the positions and words of its errors: every operation
// gives MATLAB's answer on an empty value (norm of an empty matrix is 0, [] joins as nothing, a product over an
// empty inner dimension is zero) with its tangent, or a 422 naming g with the line and column; parameters may not
// hide the language's names.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "core/groups/son_group.hpp"
#include "core/request_error.hpp"
#include "core/solve.hpp"
#include "core/user_field/program.hpp"
#include "program_error.hpp"

namespace lienewton {
namespace {

// g, its tangent along y U and dg_y's matrix on two directions, from a program and from its twin written without
// the empty values: equal bit for bit (the empty parts add exact zeros).
void expect_same_field(const std::string& with_empty, const std::string& plain) {
  SCOPED_TRACE(with_empty);
  const int n = 3;
  const auto a = user_field::compile(with_empty, n, {});
  const auto b = user_field::compile(plain, n, {});
  const SONGroup group(n);
  const Eigen::MatrixXd y = group.random(5);
  Eigen::MatrixXd u(2 * n, n);
  u << group.hat(Eigen::Vector3d(1, 2, 3)), group.hat(Eigen::Vector3d(-1, 0.5, 2));
  const Eigen::MatrixXd dy = y * u.topRows(n);
  Eigen::MatrixXd ga, dga, gb, dgb, sa, sb;
  a->eval_with_tangent(y, 0.0, dy, ga, dga);
  b->eval_with_tangent(y, 0.0, dy, gb, dgb);
  EXPECT_EQ(ga, gb);
  EXPECT_EQ(dga, dgb);
  Eigen::MatrixXd dys(2 * n, n);
  dys << dy, y * u.bottomRows(n);
  a->eval_along(y, 0.0, dys, sa);
  b->eval_along(y, 0.0, dys, sb);
  EXPECT_EQ(sa, sb);
}

TEST(UserFieldEmpty, NormOfAnEmptyMatrixIsZeroWithAZeroTangent) {
  // The crash: folded when compiled (a constant empty), or evaluated with its tangent (an empty slice of y).
  expect_same_field("g = (y - y')*norm(zeros(0))", "g = (y - y')*0");
  expect_same_field("g = (y - y')*(1 + norm(zeros(0,5)))", "g = y - y'");
  expect_same_field("g = (y - y')*(1 + norm(y(:,[])))", "g = y - y'");
  expect_same_field("g = (y - y')*(1 + norm(y([],:)))", "g = y - y'");
  expect_same_field("g = (y - y')*(2 + norm(y([],[]) * 3))", "g = (y - y')*2");
  expect_same_field("g = (y - y')*(1 + norm(sin(y(:,[]))'))", "g = y - y'");
}

TEST(UserFieldEmpty, EveryOperationTakesEmptyOperandsAsMatlabDoes) {
  // Products over an empty inner dimension are zero; empty parts of a concatenation add nothing.
  expect_same_field("g = y - y' + y(:,[])*y([],:)", "g = y - y'");
  expect_same_field("g = y - y' + zeros(3,0)*zeros(0,3)", "g = y - y'");
  expect_same_field("a = [zeros(0,3); y]; g = a - a'", "g = y - y'");
  expect_same_field("a = [y(:,[]), y, zeros(3,0)]; g = a - a'", "g = y - y'");
  expect_same_field("a = [y; y([],:)]; g = a - a'", "g = y - y'");
  // Joined into an empty value (k x 0 parts stacked, 0 x k side by side): nothing to copy, and no data to offset
  // into (an empty matrix's pointer is null: UBSan's pointer-overflow check caught [zeros(2,0); zeros(2,0)]).
  expect_same_field("a = [zeros(2,0); zeros(2,0)]; g = (y - y')*(1 + norm(a))", "g = y - y'");
  expect_same_field("a = [zeros(0,2), zeros(0,2)]; g = (y - y')*(1 + norm(a))", "g = y - y'");
  expect_same_field("a = [y(:,[]); y(:,[])]; g = (y - y')*(1 + norm(a))", "g = y - y'");
  expect_same_field("a = [y([],:), y([],:)]; g = (y - y')*(1 + norm(a))", "g = y - y'");
  // Square empties: inverse, solves, powers, trace, skew are empty or zero.
  expect_same_field("g = (y - y')*(1 + norm(inv(zeros(0))) + trace(zeros(0)))", "g = y - y'");
  expect_same_field("g = (y - y')*size(zeros(0) \\ zeros(0,2), 2)", "g = (y - y')*2");
  expect_same_field("g = (y - y')*size(zeros(2,0) / zeros(0), 1)", "g = (y - y')*2");
  expect_same_field("g = (y - y')*(1 + norm(zeros(0)^3) + norm(zeros(0)^-2) + norm(skew(zeros(0))))", "g = y - y'");
  expect_same_field("g = (y - y')*(1 + norm(y([],[])^3) + norm(inv(y([],[]))) + trace(y([],[])))", "g = y - y'");
  // A 1x1 spread over an empty value keeps it empty; entrywise functions and transposes too.
  expect_same_field("g = (y - y')*size(2 + zeros(0,3), 2)", "g = (y - y')*3");
  expect_same_field("g = (y - y')*(1 + norm(y(:,[]) .* 2 + 1) + norm(exp(y([],:))' ./ 3))", "g = y - y'");
  expect_same_field("g = (y - y')*(1 + norm(diag(zeros(1,0))) + norm(triu(zeros(0,4))) + norm(diag(zeros(0,4))))",
                    "g = y - y'");
  expect_same_field("g = (y - y')*(1 + norm(y(:,[]) .^ 2))", "g = y - y'");
  // An empty range, index and literal.
  expect_same_field("g = (y - y')*(1 + norm(1:0) + norm(y(1:0, 1)) + norm([]))", "g = y - y'");
}

TEST(UserFieldEmpty, WhatMatlabRefusesOnEmptyValuesIsA422AtItsPlace) {
  const RequestError index = compile_error("a = zeros(0,3);\ng = a(1)");
  EXPECT_EQ(index.kind(), RequestError::Kind::unprocessable);
  EXPECT_EQ(index.field(), "g");
  EXPECT_EQ(index.line(), 2);
  const RequestError cat = compile_error("a = [zeros(0,3), y];\ng = y - y'");
  EXPECT_EQ(cat.line(), 1);
  EXPECT_NE(std::string(cat.what()).find("equal numbers of rows"), std::string::npos) << cat.what();
  EXPECT_EQ(compile_error("g = (y - y')*cross(zeros(0,1), zeros(0,1))").kind(), RequestError::Kind::unprocessable);
  EXPECT_EQ(compile_error("g = y(end - 3, 1)*(y - y')").kind(), RequestError::Kind::unprocessable);
}

TEST(UserFieldErrors, ShapeOfGIsReportedOnTheLineOfG) {
  const RequestError e = compile_error("a = y;\n\nb = a';\n  g = y(:, 1)");
  EXPECT_EQ(e.field(), "g");
  EXPECT_EQ(e.line(), 4);
  EXPECT_EQ(e.column(), 3);
  EXPECT_NE(std::string(e.what()).find("g must be n\u00d7n"), std::string::npos) << e.what();
  const RequestError last = compile_error("a = y;\ny(1, :)");
  EXPECT_EQ(last.line(), 2);
}

TEST(UserFieldErrors, AnInfiniteOrHugeIndexIsNamedAsWritten) {
  const RequestError inf = compile_error("g = y(1/0, 1)");
  EXPECT_EQ(inf.column(), 8);  // at the index expression (its operator)
  EXPECT_NE(std::string(inf.what()).find("index inf is not a positive integer"), std::string::npos) << inf.what();
  const RequestError nan = compile_error("g = y(0/0, 1)");
  EXPECT_NE(std::string(nan.what()).find("index nan is not a positive integer"), std::string::npos) << nan.what();
  const RequestError minus = compile_error("g = y(1, -1/0)");
  EXPECT_NE(std::string(minus.what()).find("index -inf"), std::string::npos) << minus.what();
  const RequestError huge = compile_error("g = y(1e300, 1)");
  EXPECT_NE(std::string(huge.what()).find("index 1e+300 exceeds the size 3"), std::string::npos) << huge.what();
  const RequestError half = compile_error("g = y(0.5, 1)");
  EXPECT_NE(std::string(half.what()).find("index 0.5 is not a positive integer"), std::string::npos) << half.what();
}

TEST(UserFieldErrors, ParametersMayNotHideTheConstantOrAFunction) {
  for (const char* name : {"pi", "sin", "norm", "zeros", "transpose", "size"}) {
    SCOPED_TRACE(name);
    try {
      user_field::check_parameter(name, Eigen::MatrixXd::Ones(1, 1));
      ADD_FAILURE() << "accepted";
    } catch (const RequestError& e) {
      EXPECT_EQ(e.kind(), RequestError::Kind::unprocessable);
      EXPECT_EQ(e.field(), std::string("parameters.") + name);
    }
  }
  EXPECT_NO_THROW(user_field::check_parameter("sine", Eigen::MatrixXd::Ones(1, 1)));
  // Through a request's validation too, before the program is compiled.
  SolveRequest req;
  req.problem.g = "g = (y - y')*pi";
  req.problem.parameters = {{"pi", Eigen::MatrixXd::Constant(1, 1, 3.0)}};
  try {
    validate(req);
    ADD_FAILURE() << "validated";
  } catch (const RequestError& e) {
    EXPECT_EQ(e.field(), "parameters.pi");
  }
}

}  // namespace
}  // namespace lienewton
