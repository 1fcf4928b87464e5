// The codec names every invalid field, never converts silently, and never writes NaN/Inf.
#include "server/json_codec.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>

#include "core/fields.hpp"
#include "server/query_params.hpp"

namespace lienewton::service {
namespace {

struct Failure {
  std::string code;
  std::string field;
  bool unprocessable = false;
};

template <class Parse>
Failure failure_of(Parse parse) {
  try {
    parse();
  } catch (const RequestError& e) {
    return {error_code(e), e.field(), e.kind() == RequestError::Kind::unprocessable};
  }
  ADD_FAILURE() << "no error";
  return {};
}

Failure solve_failure(const std::string& text, Limits limits = {}) {
  return failure_of([&] { solve_request_from_json(parse_body(text), limits); });
}

TEST(JsonCodec, ParsesAFullSolveRequest) {
  const auto r = solve_request_from_json(
      parse_body(R"({"problem":"paper-sine","n":4,"h":0.25,"method":"newton-algebra","differential":"dexpinv-1",
                     "tol":1e-12,"max_iterations":50,"seed":18446744073709551615,"include_iterates":true})"),
      Limits{});
  EXPECT_EQ(r.problem.kind, ProblemKind::paper_sine);
  EXPECT_EQ(r.problem.n, 4);
  EXPECT_EQ(r.h, 0.25);
  EXPECT_EQ(r.solver.method, Method::newton_algebra);
  EXPECT_EQ(r.solver.differential, Differential::dexpinv_1);
  EXPECT_EQ(r.solver.tol, 1e-12);
  EXPECT_EQ(r.solver.max_iterations, 50);
  EXPECT_EQ(r.problem.seed, std::numeric_limits<std::uint64_t>::max());
  EXPECT_TRUE(r.solver.include_iterates);
  EXPECT_FALSE(r.problem.z.has_value());
}

TEST(JsonCodec, NamesEachInvalidSolveField) {
  const std::pair<const char*, const char*> cases[] = {
      {R"({"problem":"nope"})", "problem"},
      {R"({"problem":3})", "problem"},
      {R"({"n":3.0})", "n"},
      {R"({"n":1e300})", "n"},
      {R"({"n":4294967299})", "n"},
      {R"({"n":-3})", "n"},
      {R"({"n":1})", "n"},
      {R"({"n":65})", "n"},
      {R"({"n":"3"})", "n"},
      {R"({"h":0})", "h"},
      {R"({"h":-0.5})", "h"},
      {R"({"h":1e7})", "h"},
      {R"({"h":"0.5"})", "h"},
      {R"({"method":"newton"})", "method"},
      {R"({"differential":"exactly"})", "differential"},
      {R"({"tol":0})", "tol"},
      {R"({"tol":2})", "tol"},
      {R"({"tol":1e-17})", "tol"},
      {R"({"max_iterations":0})", "max_iterations"},
      {R"({"max_iterations":10001})", "max_iterations"},
      {R"({"max_iterations":10.5})", "max_iterations"},
      {R"({"seed":-1})", "seed"},
      {R"({"seed":1.5})", "seed"},
      {R"({"seed":18446744073709551616})", "seed"},
      {R"({"include_iterates":1})", "include_iterates"},
      {R"({"n":3,"z":[[1,0,0],[0,1,0]]})", "z"},
      {R"({"n":3,"z":[[1,0,0],[0,1,0],[0,0]]})", "z"},
      {R"({"n":3,"z":[[1,0,0],[0,1,0],[0,0,"1"]]})", "z"},
      {R"({"rigid_body":{"inertia":[1,2]}})", "rigid_body.inertia"},
      {R"({"rigid_body":{"inertia":[1,0,3]}})", "rigid_body.inertia"},
      {R"({"rigid_body":{"momentum":[1,2,"x"]}})", "rigid_body.momentum"},
      {R"({"rigid_body":[1,2,3]})", "rigid_body"},
  };
  for (const auto& [text, field] : cases) {
    const Failure f = solve_failure(text);
    EXPECT_EQ(f.field, field) << text;
    EXPECT_EQ(f.code, "invalid_field") << text;
  }
}

TEST(JsonCodec, RejectsUnknownDuplicateAndMalformed) {
  Failure f = solve_failure(R"({"n":3,"hh":0.5})");
  EXPECT_EQ(f.code, "unknown_field");
  EXPECT_EQ(f.field, "hh");
  f = solve_failure(R"({"rigid_body":{"mass":1}})");
  EXPECT_EQ(f.field, "rigid_body.mass");
  f = solve_failure(R"({"n":3,"n":4})");
  EXPECT_EQ(f.code, "duplicate_field");
  EXPECT_EQ(f.field, "n");
  EXPECT_EQ(solve_failure(R"({"n":3,)").code, "malformed_json");
  EXPECT_EQ(solve_failure("").code, "malformed_json");
  EXPECT_EQ(solve_failure("[1,2]").code, "invalid_field");
  EXPECT_EQ(solve_failure(R"({"n":2,"z":[[1,0],[0,1e400]]})").code, "malformed_json");  // overflows to Inf
  EXPECT_EQ(solve_failure(std::string(100, '[') + std::string(100, ']')).code, "malformed_json");
}

TEST(JsonCodec, NullMeansAbsentAndZGivesN) {
  const auto r = solve_request_from_json(parse_body(R"({"n":null,"z":[[0,1],[1,0]]})"), Limits{});
  EXPECT_EQ(r.problem.n, 2);
  ASSERT_TRUE(r.problem.z.has_value());
  EXPECT_EQ((*r.problem.z)(0, 1), 1.0);
}

TEST(JsonCodec, CliLimitsAcceptAnyN) {
  const auto r = solve_request_from_json(parse_body(R"({"n":500,"max_iterations":100000})"), Limits::unlimited());
  EXPECT_EQ(r.problem.n, 500);
  EXPECT_EQ(r.solver.max_iterations, 100000);
}

TEST(JsonCodec, SweepFieldsAndGridCap) {
  const auto r = sweep_request_from_json(
      parse_body(R"({"methods":["fixed-point","newton-group"],"n":[3,4],"h":[0.5,1],"differential":"exact"})"), Limits{});
  EXPECT_EQ(r.methods.size(), 2u);
  EXPECT_EQ(r.n, (std::vector<int>{3, 4}));
  EXPECT_EQ(r.h, (std::vector<double>{0.5, 1}));
  auto sweep_failure = [](const std::string& text, Limits limits = {}) {
    return failure_of([&] { sweep_request_from_json(parse_body(text), limits); });
  };
  EXPECT_EQ(sweep_failure(R"({"methods":[]})").field, "methods");
  EXPECT_EQ(sweep_failure(R"({"methods":["x"]})").field, "methods");
  EXPECT_EQ(sweep_failure(R"({"n":[3,1]})").field, "n");
  EXPECT_EQ(sweep_failure(R"({"n":3})").field, "n");
  EXPECT_EQ(sweep_failure(R"({"h":[0.5,-1]})").field, "h");
  EXPECT_EQ(sweep_failure(R"({"z":[[1]]})").code, "unknown_field");
  Limits small;
  small.max_grid_cells = 10;
  EXPECT_EQ(sweep_failure(R"({"n":[3,4],"h":[0.5,1]})", small).field, "h");  // 3 methods x 2 x 2 = 12 cells
  small.max_n = 10;
  EXPECT_EQ(sweep_failure(R"({"h":[0.5]})", small).field, "n");  // the default n goes to 15
}

TEST(JsonCodec, IntegrateAndWorkPrecision) {
  const auto r = integrate_request_from_json(
      parse_body(R"({"problem":"rigid-body","h":0.1,"t_end":2,"integrator":"dirk-cg2","frames":5})"), Limits{});
  EXPECT_EQ(r.integrator, Integrator::dirk_cg2);
  EXPECT_EQ(r.t_end, 2);
  EXPECT_EQ(r.frames, 5);
  // Without an integrator: rkmk-gauss2, or dirk-cg3 where its coupled stages would be too large to solve densely
  // (SO(n), n > 16); a request that names rkmk-gauss2 there is refused naming the field.
  const auto integrator_of = [](const std::string& text) {
    return integrate_request_from_json(parse_body(text), Limits{}).integrator;
  };
  EXPECT_EQ(integrator_of(R"({"problem":"paper-sine","n":16})"), Integrator::rkmk_gauss2);
  EXPECT_EQ(integrator_of(R"({"problem":"paper-sine","n":17})"), Integrator::dirk_cg3);
  EXPECT_EQ(integrator_of(R"({"problem":"chain","n":32})"), Integrator::rkmk_gauss2);  // bodies: sparse stages
  EXPECT_EQ(failure_of([] {
              validate(integrate_request_from_json(
                  parse_body(R"({"problem":"paper-sine","n":17,"integrator":"rkmk-gauss2"})"), Limits{}));
            }).field,
            "integrator");
  // The solver options are the solve's, linear_solver included.
  const auto gmres = integrate_request_from_json(parse_body(R"({"linear_solver":"gmres","tol":1e-10})"), Limits{});
  EXPECT_EQ(gmres.solver.linear_solver, LinearSolver::gmres);
  EXPECT_EQ(gmres.solver.tol, 1e-10);
  auto integrate_failure = [](const std::string& text) {
    return failure_of([&] { integrate_request_from_json(parse_body(text), Limits{}); });
  };
  EXPECT_EQ(integrate_failure(R"({"t_end":0})").field, "t_end");
  EXPECT_EQ(integrate_failure(R"({"integrator":"rk4"})").field, "integrator");
  EXPECT_EQ(integrate_failure(R"({"linear_solver":"qr"})").field, "linear_solver");
  EXPECT_EQ(integrate_failure(R"({"frames":-1})").field, "frames");
  EXPECT_EQ(integrate_failure(R"({"h":1e-6,"t_end":100})").field, "h");  // 1e8 steps
  // The server caps t_end (--max-t-end, default 100); the CLI's limits take any the core does (up to 1e9).
  EXPECT_EQ(integrate_failure(R"({"t_end":1000})").field, "t_end");
  try {
    integrate_request_from_json(parse_body(R"({"t_end":1000})"), Limits{});
  } catch (const RequestError& e) {
    EXPECT_NE(std::string(e.what()).find("--max-t-end"), std::string::npos) << e.what();
  }
  EXPECT_EQ(integrate_request_from_json(parse_body(R"({"t_end":1000,"h":0.5})"), Limits::unlimited()).t_end, 1000);
  EXPECT_EQ(integrate_failure(R"({"t_end":2e9})").field, "t_end");  // beyond the core's 1e9
  const auto w = work_precision_request_from_json(
      parse_body(R"({"choices":[{"integrator":"implicit-euler","method":"newton-group","differential":"exact"}],"h":[0.1,0.05]})"),
      Limits{});
  ASSERT_EQ(w.choices.size(), 1u);
  EXPECT_EQ(w.h.size(), 2u);
  auto wp_failure = [](const std::string& text) {
    return failure_of([&] { work_precision_request_from_json(parse_body(text), Limits{}); });
  };
  EXPECT_EQ(wp_failure(R"({"choices":[{"method":"x"}]})").field, "choices[0].method");
  EXPECT_EQ(wp_failure(R"({"choices":[{"solver":"x"}]})").field, "choices[0].solver");
  EXPECT_EQ(wp_failure(R"({"choices":[]})").field, "choices");
  // Without choices and h: every integrator at the problem's default steps, counted against the server's limits.
  const auto defaults = with_defaults(work_precision_request_from_json(parse_body(R"({"problem":"rigid-body"})"), Limits{}));
  EXPECT_EQ(defaults.choices.size(), std::size(kAllIntegrators));
  EXPECT_EQ(defaults.h.size(), 6u);
}

// Every request that runs solves takes the stopping rule; a bad value is a 400/422 naming the field.
TEST(JsonCodec, StoppingRuleOnEveryRequest) {
  const json algebra = parse_body(R"({"stopping":"algebra-residual"})");
  EXPECT_EQ(solve_request_from_json(parse_body("{}"), Limits{}).solver.stopping, Stopping::residual);
  EXPECT_EQ(solve_request_from_json(parse_body(R"({"stopping":"residual"})"), Limits{}).solver.stopping, Stopping::residual);
  EXPECT_EQ(solve_request_from_json(algebra, Limits{}).solver.stopping, Stopping::algebra_residual);
  EXPECT_EQ(sweep_request_from_json(algebra, Limits{}).solver.stopping, Stopping::algebra_residual);
  EXPECT_EQ(integrate_request_from_json(algebra, Limits{}).solver.stopping, Stopping::algebra_residual);
  EXPECT_EQ(work_precision_request_from_json(algebra, Limits{}).solver.stopping, Stopping::algebra_residual);
  EXPECT_EQ(work_precision_request_from_json(parse_body("{}"), Limits{}).solver.stopping, Stopping::residual);
  for (const char* bad : {R"({"stopping":"algebra"})", R"({"stopping":1})", R"({"stopping":"Residual"})"}) {
    const json body = parse_body(bad);
    for (const Failure& f : {failure_of([&] { solve_request_from_json(body, Limits{}); }),
                             failure_of([&] { sweep_request_from_json(body, Limits{}); }),
                             failure_of([&] { integrate_request_from_json(body, Limits{}); }),
                             failure_of([&] { work_precision_request_from_json(body, Limits{}); })}) {
      EXPECT_EQ(f.field, "stopping") << bad;
      EXPECT_EQ(f.code, "invalid_field") << bad;
    }
  }
}

// continuation and watchdog on every request that takes solver options (basins too), predictor on the integrating
// ones; a wrong type is refused naming the field.
TEST(JsonCodec, ContinuationWatchdogAndPredictor) {
  for (const auto& [name, flag] : {std::pair{"continuation", &SolverOptions::continuation},
                                   std::pair{"watchdog", &SolverOptions::watchdog}}) {
    const json on = json{{name, true}};
    EXPECT_FALSE(solve_request_from_json(parse_body("{}"), Limits{}).solver.*flag) << name;
    EXPECT_TRUE(solve_request_from_json(on, Limits{}).solver.*flag) << name;
    EXPECT_TRUE(sweep_request_from_json(on, Limits{}).solver.*flag) << name;
    EXPECT_TRUE(integrate_request_from_json(on, Limits{}).solver.*flag) << name;
    EXPECT_TRUE(work_precision_request_from_json(on, Limits{}).solver.*flag) << name;
    EXPECT_TRUE(basin_request_from_json(on, Limits{}).solve.solver.*flag) << name;
    for (const json& value : {json("yes"), json(1), json::array({true})}) {
      const json body = json{{name, value}};
      for (const Failure& f : {failure_of([&] { solve_request_from_json(body, Limits{}); }),
                               failure_of([&] { sweep_request_from_json(body, Limits{}); }),
                               failure_of([&] { integrate_request_from_json(body, Limits{}); }),
                               failure_of([&] { work_precision_request_from_json(body, Limits{}); }),
                               failure_of([&] { basin_request_from_json(body, Limits{}); })}) {
        EXPECT_EQ(f.field, name) << body.dump();
      }
    }
  }
  EXPECT_EQ(integrate_request_from_json(parse_body("{}"), Limits{}).predictor, Predictor::lie_euler);
  EXPECT_EQ(integrate_request_from_json(parse_body(R"({"predictor":"none"})"), Limits{}).predictor, Predictor::none);
  EXPECT_EQ(work_precision_request_from_json(parse_body(R"({"predictor":"none"})"), Limits{}).predictor, Predictor::none);
  for (const char* bad : {R"({"predictor":"newton"})", R"({"predictor":1})", R"({"predictor":true})"}) {
    const json body = parse_body(bad);
    EXPECT_EQ(failure_of([&] { integrate_request_from_json(body, Limits{}); }).field, "predictor") << bad;
    EXPECT_EQ(failure_of([&] { work_precision_request_from_json(body, Limits{}); }).field, "predictor") << bad;
  }
  const Failure on_solve = solve_failure(R"({"predictor":"lie-euler"})");  // a solve has no stages to predict
  EXPECT_EQ(on_solve.code, "unknown_field");
  EXPECT_EQ(on_solve.field, "predictor");
}

// multistart on every request that takes solver options (basins too), an integer in [0, 10000], with or without
// continuation; restarts, which it replaced, is an unknown field.
TEST(JsonCodec, Multistart) {
  const json on = json{{"multistart", 64}};
  EXPECT_EQ(solve_request_from_json(parse_body("{}"), Limits{}).solver.multistart, 0);
  EXPECT_EQ(solve_request_from_json(on, Limits{}).solver.multistart, 64);
  EXPECT_EQ(sweep_request_from_json(on, Limits{}).solver.multistart, 64);
  EXPECT_EQ(integrate_request_from_json(on, Limits{}).solver.multistart, 64);
  EXPECT_EQ(work_precision_request_from_json(on, Limits{}).solver.multistart, 64);
  EXPECT_EQ(basin_request_from_json(on, Limits{}).solve.solver.multistart, 64);
  for (const json& value : {json(-1), json(10001), json(2.5), json("8"), json(true)}) {
    const json body = json{{"multistart", value}};
    for (const Failure& f : {failure_of([&] { solve_request_from_json(body, Limits{}); }),
                             failure_of([&] { sweep_request_from_json(body, Limits{}); }),
                             failure_of([&] { basin_request_from_json(body, Limits{}); })}) {
      EXPECT_EQ(f.field, "multistart") << body.dump();
    }
  }
  EXPECT_EQ(failure_of([] { solve_request_from_json(json{{"restarts", 8}}, Limits{}); }).field, "restarts");
}

// A result says which root it is and which search found it; a continued one lists its path's points, the
// method's solves at h among them.
TEST(JsonCodec, ResultSaysWhichRoot) {
  SolveResult r;
  r.y = Eigen::MatrixXd::Identity(3, 3);
  r.iterations = 3;
  r.extra_iterations = 7;
  r.branch = Branch::continued;
  r.found_by = Search::continuation;
  r.continuation = {{PathPointKind::path, 0.5, 0.25, 0.2, 0.9, 0.5, 4, 1e-12, Status::converged},
                    {PathPointKind::final, 1.0, 0, 0, 0, 0, 3, 2e-15, Status::converged}};
  const json j = to_json(r, false);
  EXPECT_EQ(j["branch"], "continued");
  EXPECT_EQ(j["found_by"], "continuation");
  EXPECT_EQ(j["total_iterations"], 10);
  EXPECT_FALSE(j.contains("fold_h"));
  const json stages = j["continuation"]["stages"];
  ASSERT_EQ(stages.size(), 2u);
  EXPECT_EQ(stages[0]["kind"], "path");
  EXPECT_EQ(stages[0]["dh_ds"], 0.9);
  EXPECT_EQ(stages[1]["kind"], "final");
  r.status = Status::fold;
  r.fold_h = 0.75;
  r.branch = Branch::other;
  EXPECT_EQ(to_json(r, false)["fold_h"], 0.75);
  EXPECT_EQ(to_json(r, false)["status"], "fold");
}

TEST(JsonCodec, SweepResultRoundTrips) {
  SweepResult s;
  SweepCell c;
  c.method = Method::fixed_point;
  c.n = 3;
  c.h = 0.5;
  c.status = Status::diverged;
  c.reason = "grew";
  c.iterations = 7;
  c.residual = std::numeric_limits<double>::infinity();
  s.cells.push_back(c);
  const json j = to_json(s);
  EXPECT_TRUE(j["cells"][0]["residual"].is_null());
  EXPECT_TRUE(j["cells"][0]["rate"].is_null());
  const SweepResult back = sweep_result_from_json(parse_body(dump(j)), Limits{});
  ASSERT_EQ(back.cells.size(), 1u);
  EXPECT_EQ(back.cells[0].status, Status::diverged);
  EXPECT_EQ(back.cells[0].iterations, 7);
  EXPECT_TRUE(std::isnan(back.cells[0].residual));
}

TEST(JsonCodec, OutputNeverContainsNanOrInf) {
  SolveResult r;
  r.residual = std::nan("");
  r.rate = std::numeric_limits<double>::infinity();
  r.y = Eigen::MatrixXd::Constant(2, 2, std::nan(""));
  TraceRecord t;
  t.residual = -std::numeric_limits<double>::infinity();
  r.trace.push_back(t);
  const std::string text = dump(to_json(r, false));
  EXPECT_EQ(text.find("nan"), std::string::npos);
  EXPECT_EQ(text.find("inf"), std::string::npos);
  EXPECT_TRUE(parse_body(text)["residual"].is_null());
  // Invalid UTF-8 in a reason is replaced, not thrown.
  r.reason = "bad \xff byte";
  EXPECT_NO_THROW(dump(to_json(r, false)));
}

TEST(JsonCodec, ErrorBodyShape) {
  const json e = error_body("invalid_field", "h", "h must be a finite number in (0, 1e6]");
  EXPECT_EQ(dump(e), R"({"error":{"code":"invalid_field","field":"h","message":"h must be a finite number in (0, 1e6]"}})");
  EXPECT_TRUE(error_body("not_found", "", "x")["error"]["field"].is_null());
}

TEST(QueryParams, MirrorJsonFields) {
  const std::multimap<std::string, std::string> params{
      {"problem", "paper-linear"}, {"n", "3"}, {"h", "0.5"}, {"include_iterates", "true"},
      {"methods", "fixed-point,newton-group"}, {"z", "[[1,0],[0,1]]"}, {"seed", "12"}};
  const json j = query_to_json(params);
  EXPECT_EQ(j["problem"], "paper-linear");
  EXPECT_EQ(j["n"], 3);
  EXPECT_TRUE(j["n"].is_number_integer());
  EXPECT_EQ(j["h"], 0.5);
  EXPECT_EQ(j["include_iterates"], true);
  EXPECT_EQ(j["methods"], json({"fixed-point", "newton-group"}));
  EXPECT_EQ(j["z"][1][1], 1);
  const std::multimap<std::string, std::string> twice{{"n", "3"}, {"n", "4"}};
  EXPECT_EQ(failure_of([&] { query_to_json(twice); }).code, "duplicate_field");
  const std::multimap<std::string, std::string> broken{{"z", "[[1,0"}};
  EXPECT_EQ(failure_of([&] { query_to_json(broken); }).field, "z");
  // A program is text: its commas and brackets are its own (a GET of render/frames with such a g was refused).
  const std::string program = "R = y(1:3,1:3); w = y(4:6,7);\ng = [R zeros(3,4); zeros(4,7)]";
  const json text = query_to_json({{"g", program}, {"group", "SOxR"}});
  EXPECT_EQ(text["g"], program);
  EXPECT_EQ(query_to_json({{"g", "[1 2; 3 4]"}})["g"], "[1 2; 3 4]");
}

}  // namespace
}  // namespace lienewton::service

namespace lienewton::service {
namespace {

// The group is a field of every request that takes a problem: read by name ("SO" when absent); whether the name
// is registered is the core's question (422), its type the codec's.
TEST(JsonCodec, GroupIsReadByEveryRouteThatTakesAProblem) {
  const Limits limits;
  EXPECT_EQ(solve_request_from_json(parse_body("{}"), limits).problem.group, "SO");
  EXPECT_EQ(solve_request_from_json(parse_body(R"({"group":"SO"})"), limits).problem.group, "SO");
  EXPECT_EQ(sweep_request_from_json(parse_body(R"({"group":"SO","n":[2],"h":[0.5]})"), limits).problem.group, "SO");
  EXPECT_EQ(integrate_request_from_json(parse_body(R"({"group":"SO"})"), limits).problem.group, "SO");
  EXPECT_EQ(work_precision_request_from_json(parse_body(R"({"group":"SO"})"), limits).problem.group, "SO");
  EXPECT_EQ(basin_request_from_json(parse_body(R"({"group":"SO"})"), limits).solve.problem.group, "SO");
  const Failure f = solve_failure(R"({"group":3})");
  EXPECT_EQ(f.code, "invalid_field");
  EXPECT_EQ(f.field, "group");
}

// z is the group's matrix: 4 x 4 on SE(3), whose n stays 3 (n is the index whose matrices have z's size); on SO a z
// without n names n by its size; a z of another size is refused naming z, in the group's terms.
TEST(JsonCodec, ZIsSizedByTheGroup) {
  const Limits limits;
  const std::string t = "[[1,0,0,1],[0,1,0,2],[0,0,1,3],[0,0,0,1]]";
  const SolveRequest se = solve_request_from_json(parse_body(R"({"group":"SE","z":)" + t + "}"), limits);
  EXPECT_EQ(se.problem.n, 3);
  ASSERT_TRUE(se.problem.z.has_value());
  EXPECT_EQ(se.problem.z->rows(), 4);
  EXPECT_EQ(solve_request_from_json(parse_body(R"({"z":)" + t + "}"), limits).problem.n, 4);
  try {
    solve_request_from_json(parse_body(R"({"group":"SE","z":[[1,0,0],[0,1,0],[0,0,1]]})"), limits);
    ADD_FAILURE() << "read a 3 x 3 z on SE(3)";
  } catch (const RequestError& e) {
    EXPECT_EQ(error_code(e), "invalid_field");
    EXPECT_EQ(e.field(), "z");
    EXPECT_NE(std::string(e.what()).find("4 x 4 array of rows of finite numbers (an element of SE(3))"),
              std::string::npos) << e.what();
  }
}

// Every row of the field table is a field its routes take (null counts as absent) and no other route's.
TEST(JsonCodec, EachRouteTakesTheRowsOfItsRoutes) {
  const Limits limits;
  const std::pair<fields::Route, std::function<void(const json&)>> routes[] = {
      {fields::solve, [&](const json& b) { solve_request_from_json(b, limits); }},
      {fields::sweep, [&](const json& b) { sweep_request_from_json(b, limits); }},
      {fields::basins, [&](const json& b) { basin_request_from_json(b, limits); }},
      {fields::integrate, [&](const json& b) { integrate_request_from_json(b, limits); }},
      {fields::work_precision, [&](const json& b) { work_precision_request_from_json(b, limits); }}};
  for (const auto& entry : routes) {
    const auto& route = entry.first;
    const auto& read = entry.second;  // a named reference: clang 14 cannot capture a structured binding
    for (const fields::Field& row : fields::request_fields()) {
      const json body{{row.name, nullptr}};
      if (fields::find(route, row.name)) {
        EXPECT_NO_THROW(read(body)) << row.name;
      } else {
        EXPECT_EQ(failure_of([&] { read(body); }).code, "unknown_field") << row.name;
      }
    }
  }
}

}  // namespace
}  // namespace lienewton::service
