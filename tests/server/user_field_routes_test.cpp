// A user's own g(y) over HTTP: every route that takes a problem takes g (and parameters), and a program's
// fault answers 422 naming g with its line and column.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "core/groups/so3_group.hpp"
#include "server/json_codec.hpp"
#include "test_server.hpp"

namespace lienewton::service {
namespace {

using testing::post_lines;

// The paper's sine field (section 5) as a user writes it, and the rigid body with its inertia matrix J.
const std::string kSine = R"("g":"u = sin(y)*(2*y - 5*y^2); g = u - u'")";
const std::string kBody =
    R"("g":"w = J \\ (y' * m);\ng = [0 -w(3) w(2); w(3) 0 -w(1); -w(2) w(1) 0]",)"
    R"("parameters":{"J":[[1,0,0],[0,2,0],[0,0,3]],"m":[[1],[0.5],[0.2]]})";

class UserFieldRoutes : public testing::SharedServerTest {};

TEST_F(UserFieldRoutes, SolveAnswersLikeTheBuiltInTwin) {
  auto c = client();
  const std::string rest = R"(,"n":4,"h":0.5,"method":"newton-group","differential":"exact"})";
  auto user = c.Post("/api/v1/solve", "{" + kSine + rest, "application/json");
  auto built_in = c.Post("/api/v1/solve", R"({"problem":"paper-sine")" + rest, "application/json");
  ASSERT_TRUE(user && built_in);
  ASSERT_EQ(user->status, 200) << user->body;
  const json u = json::parse(user->body), b = json::parse(built_in->body);
  EXPECT_EQ(u["status"], "converged");
  EXPECT_EQ(u["iterations"], b["iterations"]);

  std::vector<json> records;
  auto streamed = post_lines(c, "/api/v1/solve", "{" + kSine + rest, "application/x-ndjson", [&](const std::string& line) {
    records.push_back(json::parse(line));
    return true;
  });
  ASSERT_TRUE(streamed);
  ASSERT_FALSE(records.empty());
  EXPECT_EQ(records.back()["type"], "result");
}

TEST_F(UserFieldRoutes, ProgramFaultsAnswer422WithLineAndColumn) {
  auto c = client();
  auto sizes = c.Post("/api/v1/solve", R"({"g":"a = y;\nb = [1 2; 3 4];\ng = a * b","h":0.5})", "application/json");
  ASSERT_TRUE(sizes);
  EXPECT_EQ(sizes->status, 422);
  const json e = json::parse(sizes->body)["error"];
  EXPECT_EQ(e["field"], "g");
  EXPECT_EQ(e["line"], 3);
  EXPECT_EQ(e["column"], 7);
  auto both = c.Post("/api/v1/solve", "{" + kSine + R"(,"problem":"paper-sine","h":0.5})", "application/json");
  ASSERT_TRUE(both);
  EXPECT_EQ(both->status, 422);
  EXPECT_EQ(json::parse(both->body)["error"]["field"], "g");
  auto off = c.Post("/api/v1/solve", R"({"g":"g = y","h":0.5})", "application/json");
  ASSERT_TRUE(off);
  EXPECT_EQ(off->status, 422) << off->body;
  auto orphan = c.Post("/api/v1/solve", R"({"parameters":{"J":1},"h":0.5})", "application/json");
  ASSERT_TRUE(orphan);
  EXPECT_EQ(orphan->status, 422);
  EXPECT_EQ(json::parse(orphan->body)["error"]["field"], "parameters");
  auto bad_value = c.Post("/api/v1/solve", R"({"g":"g = y - y'","parameters":{"J":[[1,2],[3]]},"h":0.5})", "application/json");
  ASSERT_TRUE(bad_value);
  EXPECT_EQ(bad_value->status, 400);
  EXPECT_EQ(json::parse(bad_value->body)["error"]["field"], "parameters.J");
  // A bad parameter expression and a program that does not parse: the program's own error comes first, and once
  // the program parses, the parameter's.
  auto unparsed = c.Post("/api/v1/solve", R"({"g":"a = J;\ng = y - * y'","parameters":{"J":"2 *"},"h":0.5})", "application/json");
  ASSERT_TRUE(unparsed);
  EXPECT_EQ(unparsed->status, 422);
  const json first = json::parse(unparsed->body)["error"];
  EXPECT_EQ(first["field"], "g");
  EXPECT_EQ(first["line"], 2);
  auto parsed = c.Post("/api/v1/solve", R"({"g":"a = J;\ng = y - y'","parameters":{"J":"2 *"},"h":0.5})", "application/json");
  ASSERT_TRUE(parsed);
  EXPECT_EQ(parsed->status, 422);
  EXPECT_EQ(json::parse(parsed->body)["error"]["field"], "parameters.J");
}

// The language's limits as HTTP answers: a workspace beyond the per-request budget is 413 naming g, a parameter
// that would hide pi or a function 422 naming it, an empty matrix's norm an answer (the crash).
TEST_F(UserFieldRoutes, ProgramLimitsAnswerWithTheirStatusAndField) {
  auto c = client();
  const std::string tilings =
      R"j("g":"a = y(ones(1,1000), ones(1,1000)); b = y(2*ones(1,1000), ones(1,1000)); )j"
      R"j(c = y(3*ones(1,1000), ones(1,1000)); g = (y - y')*(trace(a) + trace(b) + trace(c))")j";
  auto big = c.Post("/api/v1/sweep", "{" + tilings + R"(,"methods":["newton-group"],"n":[3],"h":[0.1,0.2,0.3,0.4],)"
                    R"("threads":4})", "application/json");
  ASSERT_TRUE(big);
  EXPECT_EQ(big->status, 413) << big->body;
  EXPECT_EQ(json::parse(big->body)["error"]["field"], "g");
  auto pi = c.Post("/api/v1/solve", R"j({"g":"g = (y - y')*pi","parameters":{"pi":3},"h":0.5})j", "application/json");
  ASSERT_TRUE(pi);
  EXPECT_EQ(pi->status, 422) << pi->body;
  EXPECT_EQ(json::parse(pi->body)["error"]["field"], "parameters.pi");
  auto norm = c.Post("/api/v1/solve", R"j({"g":"g = (y - y')*(1 + norm(zeros(0)) + norm(y(:,[])))","h":0.5})j",
                     "application/json");
  ASSERT_TRUE(norm);
  EXPECT_EQ(norm->status, 200) << norm->body;
  auto inf = c.Post("/api/v1/solve", R"j({"g":"a = y;\ng = y(1/0, 1)","h":0.5})j", "application/json");
  ASSERT_TRUE(inf);
  EXPECT_EQ(inf->status, 422);
  const json e = json::parse(inf->body)["error"];
  EXPECT_EQ(e["line"], 2);
  EXPECT_NE(e["message"].get<std::string>().find("index inf"), std::string::npos) << inf->body;
}

TEST_F(UserFieldRoutes, EveryRouteThatTakesAProblemTakesG) {
  auto c = client();
  auto sweep = c.Post("/api/v1/sweep", "{" + kSine + R"(,"methods":["newton-group"],"n":[3,4],"h":[0.25,0.5]})",
                      "application/json");
  ASSERT_TRUE(sweep);
  ASSERT_EQ(sweep->status, 200) << sweep->body;
  EXPECT_EQ(json::parse(sweep->body)["cells"].size(), 4u);
  auto basins = c.Post("/api/v1/basins", "{" + kSine + R"(,"n":3,"h":1,"size":6})", "application/json");
  ASSERT_TRUE(basins);
  EXPECT_EQ(basins->status, 200) << basins->body;
  auto integ = c.Post("/api/v1/integrate", "{" + kBody + R"(,"h":0.1,"t_end":0.5})", "application/json");
  ASSERT_TRUE(integ);
  ASSERT_EQ(integ->status, 200) << integ->body;
  EXPECT_EQ(json::parse(integ->body)["status"], "converged");
  auto wp = c.Post("/api/v1/work-precision", "{" + kBody + R"(,"t_end":0.5,"h":[0.1,0.05],)"
                     R"("choices":[{"integrator":"implicit-euler","method":"newton-group","differential":"exact"}]})", "application/json");
  ASSERT_TRUE(wp);
  EXPECT_EQ(wp->status, 200) << wp->body;
  auto heat = c.Post("/api/v1/render/heatmap",
                     "{" + kSine + R"(,"methods":["newton-group"],"n":[3,4],"h":[0.25,0.5],"metric":"iterations"})",
                     "application/json");
  ASSERT_TRUE(heat);
  EXPECT_EQ(heat->status, 200) << heat->body.substr(0, 300);
  auto frames = c.Post("/api/v1/render/frames", "{" + kBody + R"(,"h":0.1,"t_end":0.5,"width":64,"height":64})",
                       "application/json");
  ASSERT_TRUE(frames);
  EXPECT_EQ(frames->status, 200) << frames->body.substr(0, 300);
}

// A non-autonomous field, y' = y g(t, y) with g = cos(t) y'Ay (in space y' = cos(t) A y): from y(0) = I the exact
// y(1) = expm(sin(1) A). integrate reads t at each stage, and work-precision fits each integrator's order.
TEST_F(UserFieldRoutes, IntegrateReadsTime) {
  auto c = client();
  const std::string field =
      R"j("g":"g = cos(t) * (y' * A * y)","parameters":{"A":[[0,-1,0.5],[1,0,-2],[-0.5,2,0]]},)j"
      R"("t_end":1,)";
  auto integ = c.Post("/api/v1/integrate", "{" + field + R"("z":[[1,0,0],[0,1,0],[0,0,1]],"integrator":"dirk-cg2",)"
                      R"("h":0.03125})", "application/json");
  ASSERT_TRUE(integ);
  ASSERT_EQ(integ->status, 200) << integ->body;
  const json r = json::parse(integ->body);
  ASSERT_EQ(r["status"], "converged");
  Eigen::Matrix3d a, y;
  a << 0, -1, 0.5, 1, 0, -2, -0.5, 2, 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) y(i, j) = r["y"][i][j].get<double>();
  const Eigen::Matrix3d exact = SO3Group{}.exp(SO3Group{}.vee(std::sin(1.0) * a));
  const double error = (y - exact).norm();
  EXPECT_LT(error, 1e-2);  // with t read as 0 y(1) would be expm(A), far from expm(0.84 A)
  EXPECT_NEAR(r["global_error"].get<double>(), error, 1e-8 + 1e-3 * error);

  auto wp = c.Post("/api/v1/work-precision", "{" + field + R"("h":[0.0625,0.03125,0.015625,0.0078125],)"
                   R"("choices":[{"integrator":"implicit-euler"},{"integrator":"dirk-cg2"}]})", "application/json");
  ASSERT_TRUE(wp);
  ASSERT_EQ(wp->status, 200) << wp->body;
  const json series = json::parse(wp->body)["series"];
  ASSERT_EQ(series.size(), 2u);
  EXPECT_NEAR(series[0]["fitted_order"].get<double>(), 1.0, 0.15);
  EXPECT_NEAR(series[1]["fitted_order"].get<double>(), 2.0, 0.15);
}

}  // namespace
}  // namespace lienewton::service
