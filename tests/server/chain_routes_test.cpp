// The built-in chain over HTTP: POST /api/v1/integrate with "problem": "chain" on "group": "SExR^k" (n = k links)
// and its parameters as the chain object converges, reports the energy as an invariant at damping 0 only (and keeps
// it then), and its absent parameters keep their defaults; the catalog names its group, invariant and schema; bad
// parameters are 422 naming the field.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <string>

#include "core/chain_params.hpp"
#include "test_server.hpp"

namespace lienewton::service {
namespace {

class ChainRoutes : public testing::SharedServerTest {};
using testing::matrix_from_rows;

// Three default links (stiff joints, k_s = 1e5) for a tenth of their swing period (a twentieth under ASan, where a
// request of 64 steps met the server's 30 s deadline beside another test), at steps of the joints' scale, 2^-9.
#if defined(LIENEWTON_SANITIZED)
constexpr int kSteps = 32;
#else
constexpr int kSteps = 64;
#endif
const std::string kChain = R"({"problem":"chain","group":"SExR^k","n":3,"integrator":"rkmk-radau3","h":0.001953125,)"
                           R"("t_end":)" + std::to_string(kSteps / 512.0);

TEST_F(ChainRoutes, IntegrateConvergesAndReportsTheEnergyWhenUndamped) {
  const json damped = post("/api/v1/integrate", kChain + "}");
  ASSERT_EQ(damped["status"], "converged") << damped.dump().substr(0, 500);
  ASSERT_EQ(damped["steps"].size(), std::size_t{kSteps});
  const Eigen::MatrixXd y = matrix_from_rows(damped["y"]);
  EXPECT_EQ(y.rows(), 11);  // the three links' 11 x 11 matrices side by side
  EXPECT_EQ(y.cols(), 33);
  EXPECT_TRUE(damped["energy_drift"].is_null()) << "a damped chain loses energy: no invariant";
  const ChainParams p;
  const json given = post("/api/v1/integrate", kChain + R"(,"chain":)" +
                                                   json{{"mass", p.mass}, {"length", p.length},
                                                        {"stiffness", p.stiffness}, {"damping", p.damping},
                                                        {"tilt", p.tilt}}.dump() + "}");
  EXPECT_EQ(matrix_from_rows(given["y"]), matrix_from_rows(damped["y"])) << "absent parameters keep their defaults";
  const json undamped = post("/api/v1/integrate", kChain + R"(,"chain":{"damping":0}})");
  ASSERT_EQ(undamped["status"], "converged") << undamped.dump().substr(0, 500);
  ASSERT_TRUE(undamped["energy_drift"].is_number()) << undamped.dump().substr(0, 500);
  EXPECT_LE(undamped["energy_drift"].get<double>(), 1e-6);
  EXPECT_TRUE(undamped["steps"][0]["energy"].is_number());
  EXPECT_GT((matrix_from_rows(undamped["y"]) - matrix_from_rows(damped["y"])).norm(), 1e-6);
}

TEST_F(ChainRoutes, TheCatalogNamesItsGroupInvariantAndSchema) {
  auto res = client().Get("/openapi.json");
  ASSERT_TRUE(res);
  const json doc = json::parse(res->body);
  json chain;
  for (const json& p : doc["x-lienewton"]["enums"]["problem"])
    if (p["value"] == "chain") chain = p;
  EXPECT_EQ(chain["group"], "SExR^k");
  EXPECT_FALSE(chain.contains("n")) << "n is the number of links";
  EXPECT_EQ(chain["invariants"], json::array({"energy"}));
  const json& schema = doc["components"]["schemas"]["Chain"]["properties"];
  EXPECT_EQ(schema["stiffness"]["default"], 1e5);
  EXPECT_EQ(schema["damping"]["default"], 200.0);
  for (const char* name : {"mass", "inertia", "length", "gravity", "tilt"}) EXPECT_TRUE(schema.contains(name)) << name;
}

TEST_F(ChainRoutes, BadParametersAre422NamingTheField) {
  expect_422_naming("/api/v1/integrate", kChain, {
      {R"(,"chain":{"mass":-1}})", "chain.mass"},
      {R"(,"chain":{"length":0}})", "chain.length"},
      {R"(,"chain":{"inertia":[1,0,3]}})", "chain.inertia"},
      {R"(,"chain":{"stiffness":-1}})", "chain.stiffness"},
      {R"(,"chain":{"damping":-1}})", "chain.damping"},
      {R"(,"chain":{"gravity":[0,0,-2e9]}})", "chain.gravity"},
      {R"(,"chain":{"tilt":4}})", "chain.tilt"},
  });
  const json one_body = post("/api/v1/integrate", R"({"problem":"chain","group":"SExR","h":0.01})", 422);
  EXPECT_EQ(one_body["error"]["field"], "group") << one_body.dump();
  json z = json::array();  // the identities side by side as z, beside the tilt that gives y(0)
  for (int i = 0; i < 11; ++i) {
    json row = json::array();
    for (int j = 0; j < 33; ++j) row.push_back(i == j % 11 ? 1 : 0);
    z.push_back(row);
  }
  const json given_z = post("/api/v1/integrate", kChain + R"(,"z":)" + z.dump() + "}", 422);
  EXPECT_EQ(given_z["error"]["field"], "z") << given_z.dump();
  const json unknown = post("/api/v1/integrate", kChain + R"(,"chain":{"k":1}})", 400);
  EXPECT_EQ(unknown["error"]["field"], "chain.k") << unknown.dump();
}

// Every route an integrable problem runs on takes the chain: a streamed integration, a work-precision diagram, a
// stability sweep of its implicit Euler equation over h and k, and the frames and invariants renders.
TEST_F(ChainRoutes, RunsOnEveryIntegrationRoute) {
  auto c = client();
  int steps = 0;
  std::string terminal;
  testing::post_lines(c, "/api/v1/integrate", kChain + "}", "application/x-ndjson",
                      [&](const std::string& line) {
                        const json record = json::parse(line);
                        if (record["type"] == "step") ++steps;
                        if (record["type"] != "step") terminal = record["type"];
                        return true;
                      });
  EXPECT_EQ(steps, kSteps);
  EXPECT_EQ(terminal, "result");

  const json wp = post("/api/v1/work-precision", R"({"problem":"chain","group":"SExR^2","t_end":0.125,)"
                                                  R"("h":[0.0078125,0.00390625],"choices":[{"integrator":"dirk-cg2"},)"
                                                  R"({"integrator":"rkmk-radau3"}]})");
  ASSERT_EQ(wp["series"].size(), 2u) << wp.dump().substr(0, 500);
  for (const json& series : wp["series"])
    for (const json& p : series["points"]) {
      EXPECT_EQ(p["status"], "converged") << series["choice"].dump();
      EXPECT_GT(p["error"].get<double>(), 0.0) << series["choice"].dump();
    }

  const json sweep = post("/api/v1/sweep", R"({"problem":"chain","group":"SExR^k","n":[2,3],"h":[0.001,0.01],)"
                                           R"("methods":["newton-group"]})");
  ASSERT_EQ(sweep["cells"].size(), 4u) << sweep.dump().substr(0, 500);
  for (const json& cell : sweep["cells"])
    EXPECT_TRUE(cell["status"] == "converged" || cell["status"] == "stagnated") << cell.dump();

  for (const char* route : {"/api/v1/render/frames", "/api/v1/render/invariants"}) {
    auto png = c.Post(route, kChain + R"(,"chain":{"damping":0},"frames":4,"width":96,"height":96})",
                      "application/json");
    ASSERT_TRUE(png);
    EXPECT_EQ(png->status, 200) << route << ": " << png->body;
    EXPECT_EQ(png->body.substr(1, 3), "PNG") << route;
  }
}

}  // namespace
}  // namespace lienewton::service
