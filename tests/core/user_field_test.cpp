// A user's own g(y) written in MATLAB notation (core/user_field): the paper's fields and the rigid body as
// programs against their built-in twins on the section-5 grid, the exact differential against difference
// quotients, quadratic convergence on a field with no twin, and hostile programs refused or failing cleanly.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "core/integrators/methods.hpp"
#include "core/integrate.hpp"
#include "core/order_fit.hpp"
#include "core/groups/se3_group.hpp"
#include "core/request_error.hpp"
#include "core/solve.hpp"
#include "core/user_field/program.hpp"
#include "core/user_field/user_vector_field.hpp"
#include "gtest_printers.hpp"
#include "paper_request.hpp"
#include "program_error.hpp"
#include "residual_oracle.hpp"

namespace lienewton {
namespace {

constexpr const char* kPaperLinear = "g = diag(diag(y,1),1) - diag(diag(y,1),-1)";
constexpr const char* kPaperSine = "u = sin(y)*(2*y - 5*y^2); g = u - u'";
// The free rigid body with the inertia J (principal moments) and spatial momentum m as parameters.
constexpr const char* kRigidBody =
    "w = (y' * m) ./ J;\n"
    "g = [0 -w(3) w(2); w(3) 0 -w(1); -w(2) w(1) 0]";

SolveRequest as_program(SolveRequest req, const char* source) {
  req.problem.g = source;
  return req;
}

// Whether a cell is erratic, its outcome decided by rounding, so that a program's rounding may decide it
// otherwise: the rounding floor of its residual is well above tol (it converged below the floor by luck), or a 1e-15
// turn of z already changes the built-in's status or iteration count (a long wandering run), or a 1e-15 relative
// change of g does (a difference quotient amplifies g's rounding 1e8-fold; an ill-conditioned step, more).
bool erratic(const SolveRequest& req, const SolveResult& built_in, const char* source) {
  if (built_in.floor >= 10 * req.solver.tol) return true;
  auto differs = [&](const SolveResult& r) {
    return r.status != built_in.status || r.total_iterations() != built_in.total_iterations();
  };
  const SONGroup group(req.problem.n);
  SolveRequest turned = req;
  turned.problem.z = group.times_exp(req.problem.start(), Eigen::VectorXd::Constant(group.dim(), 1e-15));
  if (differs(solve(turned))) return true;
  SolveRequest scaled = req;
  scaled.problem.g = std::string(source) + "; g = g * (1 + 1e-15)";
  return differs(solve(scaled));
}

// The same status and iteration count, and residuals agreeing to 1e-14 relative to the size of f's terms
// (h ||g(y)|| at the root, at least 1) or within both runs' rounding floors when those are larger, wherever the built-in converges within 15 iterations on a cell that is not erratic.
void expect_twins(const char* source, ProblemKind kind, const std::vector<int>& dims) {
  int compared = 0, skipped = 0;
  for (int n : dims)
    for (int e = -10; e <= 10; ++e)
      for (Method m : kAllMethods)
        for (Differential d : {Differential::exact, Differential::finite_difference}) {
          if (m == Method::fixed_point && d != Differential::exact) continue;
          const double h = std::ldexp(1.0, e);
          const SolveRequest req = paper_request(kind, n, h, m, d);
          const SolveResult built_in = solve(req);
          if (built_in.status != Status::converged || built_in.total_iterations() > 15) continue;
          if (erratic(req, built_in, source)) {
            ++skipped;
            continue;
          }
          const SolveResult user = solve(as_program(req, source));
          SCOPED_TRACE(std::string(to_string(kind)) + " n=" + std::to_string(n) + " h=2^" + std::to_string(e) + " " +
                       std::string(to_string(m)) + " " + std::string(to_string(d)));
          const SONGroup group(n);
          const double scale = std::max(1.0, h * make_field(group, req.problem)->g(group.element(built_in.y)).norm());
          EXPECT_EQ(user.status, built_in.status) << user.reason;
          EXPECT_EQ(user.total_iterations(), built_in.total_iterations()) << user.reason << " / " << built_in.reason;
          EXPECT_LE(std::abs(user.residual - built_in.residual), std::max(1e-14 * scale, 2 * built_in.floor));
          ++compared;
        }
  EXPECT_GT(compared, 2 * skipped) << "most converging cells are not erratic";
}

TEST(UserField, PaperFieldsAsProgramsMatchTheBuiltInsOnTheGrid) {
  // The default suite takes four N of the paper's 2..15; LIENEWTON_FULL_GRID=1 runs all of them.
  std::vector<int> dims{2, 3, 4, 7};
  if (const char* full = std::getenv("LIENEWTON_FULL_GRID"); full && std::string(full) == "1") {
    dims.clear();
    for (int n = 2; n <= 15; ++n) dims.push_back(n);
  }
  expect_twins(kPaperLinear, ProblemKind::paper_linear, dims);
  expect_twins(kPaperSine, ProblemKind::paper_sine, dims);
}

TEST(UserField, RigidBodyWithInertiaAsParameterMatchesTheBuiltIn) {
  int compared = 0;
  for (double h : {0.01, 0.1, 0.5, 1.0})
    for (Method m : kAllMethods)
      for (Differential d : {Differential::exact, Differential::finite_difference}) {
        SolveRequest req = paper_request(ProblemKind::rigid_body, 3, h, m, d);
        req.problem.rigid_body = RigidBodyParams{};
        const SolveResult built_in = solve(req);
        if (built_in.status != Status::converged || built_in.total_iterations() > 15) continue;
        SolveRequest user_req = as_program(req, kRigidBody);
        user_req.problem.parameters["J"] = req.problem.rigid_body.inertia;
        user_req.problem.parameters["m"] = req.problem.rigid_body.momentum;
        const SolveResult user = solve(user_req);
        EXPECT_EQ(user.status, built_in.status) << user.reason;
        EXPECT_EQ(user.total_iterations(), built_in.total_iterations()) << "h=" << h;
        EXPECT_LE(std::abs(user.residual - built_in.residual), 1e-14 * std::max(1.0, built_in.residual));
        ++compared;
      }
  EXPECT_GT(compared, 0);
}

// A field with no built-in twin, using most of the language.
TEST(UserField, ExactDifferentialAgainstCentralDifferencesHasSlopeTwo) {
  const int n = 4;
  const char* source =
      "A = eye(4) + 0.5 * (y' * y);\n"
      "u = tanh(y) / A + diag(diag(y,1),1).^2 + exp(y) ./ (2 + cos(y)) + trace(y) * y + norm(y(:,1)) * y^3 "
      "+ sqrt(abs(y) + 1) .* sinh(y(end:-1:1, :)) + inv(A) * [y(1:2, :); cosh(y(3:end, :))];\n"
      "g = skew(u)";
  const SONGroup group(n);
  const UserVectorField<SONGroup> field(group, user_field::compile(source, n, {}));
  const Eigen::MatrixXd y = group.random(7);
  Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(group.dim(), -1.0, 1.3);
  const Eigen::VectorXd exact = field.dg(y, u);
  auto error = [&](double s) {
    const Eigen::VectorXd quotient = (field.g(group.times_exp(y, s * u)) - field.g(group.times_exp(y, -s * u))) / (2 * s);
    return (quotient - exact).norm();
  };
  const double e1 = error(1e-2), e2 = error(5e-3);
  const double slope = std::log2(e1 / e2);
  EXPECT_NEAR(slope, 2.0, 0.2) << e1 << " " << e2;
  EXPECT_LT(e1, 1e-2 * exact.norm());
}

TEST(UserField, NewtonConvergesQuadraticallyOnAFieldWithNoTwin) {
  for (Method m : {Method::newton_group, Method::newton_algebra}) {
    SolveRequest req = paper_request(ProblemKind::paper_linear, 4, 0.25, m, Differential::exact);
    req.problem.g = "u = sin(y) * y^2 + 0.3 * exp(y) + y(:, end) * y(1, :); g = skew(u)";
    const SolveResult r = solve(req);
    ASSERT_EQ(r.status, Status::converged) << r.reason;
    ASSERT_TRUE(r.rate.has_value());
    EXPECT_NEAR(*r.rate, 2.0, 0.2);
  }
}

// y' = y g(t, y) with g = cos(t) y'Ay, A constant skew: in space y' = cos(t) A y, so y(t) = expm(sin(t) A) y0
// exactly. The directions commute, so an integrator's error is its quadrature's of cos: its order, never exact.
constexpr const char* kNonAutonomous = "g = cos(t) * (y' * A * y)";
Eigen::MatrixXd skew_a(const SONGroup& group) { return group.hat(Eigen::VectorXd::LinSpaced(group.dim(), -1.0, 1.5)); }

TEST(UserField, NonAutonomousFieldReachesEachIntegratorsOrderAgainstTheClosedForm) {
  const int n = 4;
  const SONGroup group(n);
  const Eigen::MatrixXd a = skew_a(group);
  for (Integrator integrator : kAllIntegrators) {
    // Steps whose errors stay far above rounding: orders 5 and 6 reach 1e-13 by h = 1/16.
    const double coarsest = order_of(integrator) >= 5 ? 1.0 : 1.0 / 16;
    std::vector<double> hs, errors;
    for (double h : {coarsest, coarsest / 2, coarsest / 4, coarsest / 8}) {
      IntegrateRequest req;
      req.problem.g = kNonAutonomous;
      req.problem.parameters["A"] = a;
      req.problem.n = n;
      req.h = h;
      req.t_end = 1.0;
      req.integrator = integrator;
      const IntegrateResult r = integrate(req);
      ASSERT_EQ(r.status, Status::converged) << r.reason;
      const Eigen::MatrixXd exact = group.exp(group.vee(std::sin(1.0) * a)) * req.problem.start();
      hs.push_back(h);
      errors.push_back((r.y - exact).norm());
      // The reference solution (RKMK4) reads t too: its error is the closed form's, to the reference's accuracy.
      EXPECT_NEAR(*r.global_error, errors.back(), 1e-8 + 1e-3 * errors.back()) << "h=" << h;
    }
    SCOPED_TRACE(std::string(to_string(integrator)));
    EXPECT_NEAR(fitted_order(hs, errors).value(), order_of(integrator), 0.15)
        << errors[0] << " " << errors[1] << " " << errors[2] << " " << errors[3];
    EXPECT_LT(errors.back(), 0.1);
  }
}

TEST(UserField, TimeIsZeroInASolve) {
  SolveRequest req = paper_request(ProblemKind::paper_linear, 4, 0.5, Method::newton_group, Differential::exact);
  req.problem.parameters["A"] = skew_a(SONGroup(4));
  SolveRequest with_t = req, without_t = req;
  with_t.problem.g = "g = (1 + t) * (y' * A * y) + sin(t) * A";
  without_t.problem.g = "g = y' * A * y";
  const SolveResult a = solve(with_t), b = solve(without_t);
  ASSERT_EQ(a.status, Status::converged) << a.reason;
  EXPECT_EQ(a.total_iterations(), b.total_iterations());
  EXPECT_EQ(a.y, b.y);
}

// A field on SE(3) with no twin: y is the 4 x 4 [[R, p], [0, 1]], indexing takes R and p apart, and the value is
// [[hat(w), v], [0, 0]] in se(3): a rigid body's angular velocity pushed by p, and a velocity along R's z-axis.
constexpr const char* kSe3Field =
    "R = y(1:3, 1:3); p = y(1:3, 4);\n"
    "w = (R' * [0.6; 0.8; 0.5]) ./ [1; 2; 3] + 0.1 * sin(p);\n"
    "v = R' * [0; 0; 1] + 0.2 * cross(w, R' * p);\n"
    "g = [0 -w(3) w(2) v(1); w(3) 0 -w(1) v(2); -w(2) w(1) 0 v(3); 0 0 0 0]";

// kSe3Field written again in C++, for the oracle.
Eigen::MatrixXd se3_field(const Eigen::MatrixXd& y) {
  const Eigen::Matrix3d r = y.topLeftCorner(3, 3);
  const Eigen::Vector3d p = y.topRightCorner(3, 1);
  const Eigen::Vector3d w = (r.transpose() * Eigen::Vector3d(0.6, 0.8, 0.5)).cwiseQuotient(Eigen::Vector3d(1, 2, 3)) +
                            0.1 * Eigen::Vector3d(p.array().sin());
  const Eigen::Vector3d v = r.transpose() * Eigen::Vector3d::UnitZ() + 0.2 * w.cross(r.transpose() * p);
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(4, 4);
  g << 0, -w(2), w(1), v(0), w(2), 0, -w(0), v(1), -w(1), w(0), 0, v(2), 0, 0, 0, 0;
  return g;
}

// Newton on a user's field on SE(3), asked for by name, with the exact differential: quadratic (rate within 0.2 of
// 2), and y solves (1.1) by Eigen's own matrix exponential: ||y - z expm(h g(y))||_F <= 1e-12, y in SE(3). At h = 2
// the run takes five steps from ||f|| = 2.6, so the rate is read where the iteration is asymptotic (at h <= 1 it
// takes four, and the rate of the last pair, still pre-asymptotic, is 1.6 to 2.3 as it is on SO(3)).
TEST(UserField, NewtonConvergesQuadraticallyOnSE3) {
  for (Method m : {Method::newton_group, Method::newton_algebra}) {
    SolveRequest req = paper_request(ProblemKind::paper_linear, 3, 2.0, m, Differential::exact);
    req.problem.group = "SE";
    req.problem.g = kSe3Field;
    const SolveResult r = solve(req);
    ASSERT_EQ(r.status, Status::converged) << r.reason;
    ASSERT_TRUE(r.rate.has_value());
    EXPECT_NEAR(*r.rate, 2.0, 0.2) << to_string(m);
    const Eigen::MatrixXd z = req.problem.start();
    ASSERT_EQ(r.y.rows(), 4);
    EXPECT_LE((r.y - z * oracle_exp(req.h * se3_field(r.y))).norm(), 1e-12) << to_string(m);
    EXPECT_EQ(SE3Group{}.not_an_element(r.y, "y"), "") << r.y;
  }
}

// dg_y's matrix takes the tangents of all basis directions in one pass (each product rule on the directions side
// by side, the rarer operations one direction at a time inside it); it agrees with dg_y along each direction alone,
// for every operation of the language, on SO(4) and SE(3), and on SO(40), whose 780 directions do not fit one pass.
TEST(UserField, DgMatrixAgreesWithEachDirectionAlone) {
  const auto each_direction_alone = [](const auto& group, const auto& field, const auto& y) {
    const Eigen::MatrixXd m = field.dg_matrix(group, y);
    double worst = 0;
    for (int i = 0; i < group.dim(); ++i) {
      const Eigen::VectorXd alone = field.dg(y, basis_vector(group, i));
      worst = std::max(worst, (m.col(i) - alone).norm() / std::max(1.0, alone.norm()));
    }
    return worst;
  };
  const char* every_operation =
      "A = eye(4) + 0.5 * (y' * y); v = y(:, 2); w = y(2:4, 1);\n"
      "u = tanh(y) / A + A \\ y + diag(diag(y,1),1).^2 + exp(y) ./ (2 + cos(y)) + trace(y) * y + norm(y(:,1)) * y^3 "
      "+ sqrt(abs(y) + 1) .* sinh(y(end:-1:1, :)) + inv(A) * [y(1:2, :); cosh(y(3:end, :))] + y^-2 + (y + 2).^y "
      "+ triu(y, 1) * tril(y) + transpose(y) .* y + 2 + y(3) + [cross(w, w.^2); 1] * v' + norm(y) * log(2 + y.*y) "
      "- tan(y / 4) + y.' ./ (3 + y);\n"
      "g = skew(u) + (u - u')";
  const SONGroup so4(4);
  const UserVectorField<SONGroup> on_so4(so4, user_field::compile(every_operation, 4, {}));
  EXPECT_LE(each_direction_alone(so4, on_so4, so4.random(7)), 1e-12);
  const SE3Group se3;
  const UserVectorField<SE3Group> on_se3(se3, user_field::compile(kSe3Field, 4, {}));
  EXPECT_LE(each_direction_alone(se3, on_se3, se3.random(3)), 1e-12);
  const SONGroup so40(40);
  const UserVectorField<SONGroup> on_so40(so40, user_field::compile("u = y * y; g = u - u'", 40, {}));
  EXPECT_LE(each_direction_alone(so40, on_so40, so40.random(5)), 1e-12);
}

// The value is checked against se(3) by SE(3)'s hat and vee: a skew 4 x 4 value (in so(4), accepted on SO(4)) has
// a last row and is refused, naming g; so is a value with a symmetric part in its rotation block.
TEST(UserField, ValueOffSe3IsRefusedNamingG) {
  for (const char* source : {"g = y - y'", "g = [eye(3) y(1:3, 4); 0 0 0 0]"}) {
    SolveRequest req = paper_request(ProblemKind::paper_linear, 3, 0.5, Method::newton_group, Differential::exact);
    req.problem.group = "SE";
    req.problem.g = source;
    try {
      solve(req);
      ADD_FAILURE() << "solved a field off se(3): " << source;
    } catch (const RequestError& e) {
      EXPECT_EQ(e.field(), "g");
      EXPECT_NE(std::string(e.what()).find("algebra of SE(3)"), std::string::npos) << e.what();
    }
  }
}

TEST(UserField, ErrorsNameTheLineColumnAndSpeakMatlab) {
  const RequestError sizes = compile_error("a = y;\nb = [1 2; 3 4];\ng = a * b");
  EXPECT_EQ(sizes.kind(), RequestError::Kind::unprocessable);
  EXPECT_EQ(sizes.field(), "g");
  EXPECT_EQ(sizes.line(), 3);
  EXPECT_EQ(sizes.column(), 7);
  EXPECT_NE(std::string(sizes.what()).find("matrix sizes 3\u00d73 and 2\u00d72 do not agree for *"), std::string::npos)
      << sizes.what();
  const RequestError unknown = compile_error("g = sinh2(y)");
  EXPECT_NE(std::string(unknown.what()).find("unknown function or variable 'sinh2'"), std::string::npos);
  EXPECT_EQ(unknown.column(), 5);
  const RequestError shape = compile_error("g = y(:, 1)");
  EXPECT_NE(std::string(shape.what()).find("g must be n\u00d7n"), std::string::npos) << shape.what();
  EXPECT_GT(compile_error("g = (y + ").line(), 0);
  // A bracket left open is reported where it opens, not past the program's last line.
  const RequestError open = compile_error("a = (y + 1\nb = a * 2\ng = b - b'");
  EXPECT_EQ(open.line(), 1);
  EXPECT_EQ(open.column(), 5);
  EXPECT_NE(std::string(open.what()).find("this '(' is never closed"), std::string::npos) << open.what();
  const RequestError row = compile_error("u = y;\ng = [u(1, 1) 0 0; 0 0 0; 0 0 0");
  EXPECT_EQ(row.line(), 2);
  EXPECT_EQ(row.column(), 5);
  EXPECT_GT(compile_error("g = y(4, 1)").line(), 0);
  EXPECT_GT(compile_error("g = y ^ 0.5").line(), 0);
  EXPECT_GT(compile_error("g = 'abc'").line(), 0);
}

TEST(UserField, HostileProgramsAreRefusedBeforeTheyRun) {
  EXPECT_GT(compile_error(std::string(1 << 20, ' ') + "g = y").line(), 0);                  // 1 MB source
  EXPECT_GT(compile_error(std::string(5000, '(') + "y" + std::string(5000, ')')).line(), 0);  // deep nesting
  EXPECT_GT(compile_error(std::string(5000, '-') + "y").line(), 0);
  std::string literal = "g = [";
  for (int i = 0; i < 30000; ++i) literal += "1 ";
  EXPECT_GT(compile_error(literal + "]").line(), 0);                                          // too many terms
  EXPECT_GT(compile_error("a = zeros(100000); g = y").line(), 0);                            // huge matrix
  EXPECT_GT(compile_error("a = ones(900) * ones(900) * ones(900) * ones(900); g = y").line(), 0);  // cost
  EXPECT_GT(compile_error("g = [1 2 3]", 3, {{"J", Eigen::MatrixXd::Ones(2, 2)}}).line(), 0);
}

// Constant operands are folded when compiled (the fuzzer's first find: 3*4 * ... folded with no tangents).
TEST(UserField, ConstantsAreFoldedAndShared) {
  const auto folded = user_field::compile("u = sin(y)*(3*4 * -y^2 + J*J); g = -4*u' + 4*u", 3,
                                          {{"J", Eigen::MatrixXd::Identity(3, 3)}});
  // The same with its constants written out: 3*4 and J*J cost no instruction, y^2 is y*y.
  const auto plain = user_field::compile("u = sin(y)*(12 * -(y*y) + K); g = -4*u' + 4*u", 3,
                                         {{"K", Eigen::MatrixXd::Identity(3, 3)}});
  const Eigen::MatrixXd y = SONGroup(3).random(2);
  Eigen::MatrixXd a, b;
  folded->eval(y, 0.0, a);
  plain->eval(y, 0.0, b);
  EXPECT_EQ(a, b);
  EXPECT_EQ(folded->instructions(), plain->instructions());
}

// Programs that compile but fail as they run end with a clean status, never NaN in the result.
TEST(UserField, NumericalTroubleEndsWithACleanStatus) {
  for (const char* source : {"u = y^1000000000; g = u - u'", "u = inv(y - y'); g = u - u'",
                             "u = log(y - 2); g = u - u'", "u = y ./ (y - y); g = u - u'"}) {
    SolveRequest req = paper_request(ProblemKind::paper_linear, 3, 0.5, Method::newton_group, Differential::exact);
    req.problem.g = source;
    const SolveResult r = solve(req);
    EXPECT_NE(r.status, Status::converged) << source;
    EXPECT_TRUE(r.y.allFinite()) << source;
  }
}

TEST(UserField, ValueOffTheAlgebraIsRefusedNamingG) {
  SolveRequest req = paper_request(ProblemKind::paper_linear, 3, 0.5, Method::newton_group, Differential::exact);
  req.problem.g = "g = y";
  try {
    solve(req);
    ADD_FAILURE() << "solved a field off the algebra";
  } catch (const RequestError& e) {
    EXPECT_EQ(e.field(), "g");
    EXPECT_NE(std::string(e.what()).find("algebra"), std::string::npos) << e.what();
  }
}

// The values of t alone are formed once per t, and again when t changes: the same program evaluated at t1, t2
// and t1 again answers as the program with t written out.
TEST(UserField, ValuesOfTAloneFollowTheTime) {
  const auto program = user_field::compile("B = t^2 * eye(3) + [0 t 0; -t 0 0; 0 0 0]; g = B * y - y' * B'", 3, {});
  const Eigen::MatrixXd y = SONGroup(3).random(4), dy = Eigen::MatrixXd::Ones(3, 3);
  for (double t : {0.5, -2.0, 0.5, 0.0}) {
    Eigen::MatrixXd b = t * t * Eigen::MatrixXd::Identity(3, 3);
    b(0, 1) = t;
    b(1, 0) = -t;
    Eigen::MatrixXd g, dg;
    program->eval_with_tangent(y, t, dy, g, dg);
    EXPECT_LE((g - (b * y - y.transpose() * b.transpose())).norm(), 1e-14) << "t=" << t;
    EXPECT_LE((dg - (b * dy - dy.transpose() * b.transpose())).norm(), 1e-14) << "t=" << t;
  }
  // t is not known when compiled: it cannot size, index or raise a matrix.
  EXPECT_GT(compile_error("a = zeros(t); g = y - y'").line(), 0);
  EXPECT_GT(compile_error("g = y(1:t, :)").line(), 0);
  EXPECT_GT(compile_error("g = y^t - (y^t)'").line(), 0);
}

// g and then dg_y at the same y share the values of one pass; every change of y (by a single bit: -0 for 0) or of t
// forms them anew. Each call is compared with a freshly compiled program, which has nothing kept.
TEST(UserField, KeptValuesAreThoseOfTheSameYAndTime) {
  const std::string source = "u = sin(y) * exp(y/4) + inv(eye(3) + y'*y) .* y + t*y^3; g = u - u'";
  const auto program = user_field::compile(source, 3, {});
  const Eigen::MatrixXd y1 = SONGroup(3).random(1), y2 = SONGroup(3).random(2);
  const Eigen::MatrixXd d1 = Eigen::MatrixXd::Ones(3, 3), d2 = Eigen::MatrixXd::Identity(3, 3);
  struct Call { const Eigen::MatrixXd* y; double t; const Eigen::MatrixXd* dy; };
  const std::vector<Call> calls = {{&y1, 0, nullptr}, {&y1, 0, &d1}, {&y1, 0, &d2}, {&y2, 0, &d1},
                                   {&y1, 0.5, nullptr}, {&y1, 0.5, &d2}, {&y1, 0, &d2}, {&y2, 0, nullptr},
                                   {&y2, 0, nullptr}, {&y2, 0.5, &d1}, {&y2, 0.5, nullptr}};
  // What each call must answer, from fresh programs first (a thread keeps one program's values at a time).
  std::vector<Eigen::MatrixXd> want_g(calls.size()), want_dg(calls.size());
  for (std::size_t k = 0; k < calls.size(); ++k)
    user_field::compile(source, 3, {})->eval_with_tangent(*calls[k].y, calls[k].t, calls[k].dy ? *calls[k].dy : d1,
                                                          want_g[k], want_dg[k]);
  // A basis U_1, U_2 (the directions y U_1, y U_2).
  const Eigen::MatrixXd u1 = Eigen::MatrixXd::Ones(3, 3), u2 = Eigen::MatrixXd::Identity(3, 3);
  std::vector<Eigen::MatrixXd> want_basis(2), unused(2);
  for (int i = 0; i < 2; ++i)
    user_field::compile(source, 3, {})->eval_with_tangent(y2, 0.5, y2 * (i == 0 ? u1 : u2), unused[i], want_basis[i]);
  for (std::size_t k = 0; k < calls.size(); ++k) {
    const Call& c = calls[k];
    Eigen::MatrixXd g, dg;
    if (c.dy) program->eval_with_tangent(*c.y, c.t, *c.dy, g, dg);
    else program->eval(*c.y, c.t, g);
    EXPECT_LE((g - want_g[k]).norm(), 1e-14 * want_g[k].norm()) << "call " << k;
    if (c.dy) {
      EXPECT_LE((dg - want_dg[k]).norm(), 1e-14 * want_dg[k].norm()) << "call " << k;
    }
  }
  // Every direction of a basis at once, after g at that y (the tangents through products of wider matrices, so
  // equal to rounding).
  Eigen::MatrixXd dys(6, 3), dgs;
  dys << y2 * u1, y2 * u2;
  program->eval_along(y2, 0.5, dys, dgs);
  for (int i = 0; i < 2; ++i)
    EXPECT_LE((dgs.middleRows(3 * i, 3) - want_basis[i]).norm(), 1e-13 * want_basis[i].norm());
  // 0 and -0 are different inputs: 1/0 = Inf, 1/-0 = -Inf.
  const auto reciprocal = user_field::compile("v = 1./y; g = v - v'", 3, {});
  Eigen::MatrixXd y0{{1, 0, 2}, {3, 4, 5}, {6, 7, 8}}, g_plus, g_minus;
  reciprocal->eval(y0, 0, g_plus);
  y0(0, 1) = -0.0;
  reciprocal->eval(y0, 0, g_minus);
  EXPECT_EQ(g_plus(0, 1), std::numeric_limits<double>::infinity());
  EXPECT_EQ(g_minus(0, 1), -std::numeric_limits<double>::infinity());
}

// A parameter may be written as an expression of constants: evaluated once, exactly as the program's constants.
TEST(UserField, ParameterExpressionsOfConstants) {
  EXPECT_DOUBLE_EQ(user_field::constant_value("pi/4", "parameters.a")(0, 0), std::numbers::pi / 4);
  EXPECT_DOUBLE_EQ(user_field::constant_value("1/3", "parameters.a")(0, 0), 1.0 / 3.0);
  const Eigen::MatrixXd j = user_field::constant_value("0.1*eye(3)", "parameters.J");
  EXPECT_EQ(j, Eigen::MatrixXd(0.1 * Eigen::MatrixXd::Identity(3, 3)));
  EXPECT_EQ(user_field::constant_value("[1 2; 3 4]'", "parameters.M"), (Eigen::MatrixXd{{1, 3}, {2, 4}}));
  EXPECT_EQ(user_field::constant_value("c = cos(pi); [c; 2*c]", "parameters.v"), (Eigen::MatrixXd{{-1}, {-2}}));
  // It reads no y or t, and a fault names the parameter with its line and column.
  // One value: a list of numbers outside brackets, two lines, or an assignment alone is not one.
  for (const char* bad : {"y(1,1)", "2*t", "1 +", "", "undefined_name", "1,2", "2\n3", "a = 2", "1; c = 2"}) {
    try {
      user_field::constant_value(bad, "parameters.k");
      ADD_FAILURE() << bad << " was accepted";
    } catch (const RequestError& e) {
      EXPECT_EQ(e.field(), "parameters.k") << bad;
      EXPECT_EQ(e.kind(), RequestError::Kind::unprocessable) << bad;
      EXPECT_GE(e.line(), 1) << bad;
      EXPECT_EQ(std::string(e.what()).rfind("parameters.k: ", 0), 0u) << e.what();
    }
  }
}

}  // namespace
}  // namespace lienewton
