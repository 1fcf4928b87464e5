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

// Three default links (stiff joints, k_s = 1e5) for a tenth of their swing period, at steps of the joints' scale.
constexpr const char* kChain =
    R"({"problem":"chain","group":"SExR^k","n":3,"integrator":"rkmk-radau3","h":0.001953125,"t_end":0.125)";

TEST_F(ChainRoutes, IntegrateConvergesAndReportsTheEnergyWhenUndamped) {
  const json damped = post("/api/v1/integrate", std::string(kChain) + "}");
  ASSERT_EQ(damped["status"], "converged") << damped.dump().substr(0, 500);
  ASSERT_EQ(damped["steps"].size(), 64u);
  const Eigen::MatrixXd y = matrix_from_rows(damped["y"]);
  EXPECT_EQ(y.rows(), 11);  // the three links' 11 x 11 matrices side by side
  EXPECT_EQ(y.cols(), 33);
  EXPECT_TRUE(damped["energy_drift"].is_null()) << "a damped chain loses energy: no invariant";
  const ChainParams p;
  const json given = post("/api/v1/integrate", std::string(kChain) + R"(,"chain":)" +
                                                   json{{"mass", p.mass}, {"length", p.length},
                                                        {"stiffness", p.stiffness}, {"damping", p.damping},
                                                        {"tilt", p.tilt}}.dump() + "}");
  EXPECT_EQ(matrix_from_rows(given["y"]), matrix_from_rows(damped["y"])) << "absent parameters keep their defaults";
  const json undamped = post("/api/v1/integrate", std::string(kChain) + R"(,"chain":{"damping":0}})");
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
  const json given_z = post("/api/v1/integrate", std::string(kChain) + R"(,"z":)" + z.dump() + "}", 422);
  EXPECT_EQ(given_z["error"]["field"], "z") << given_z.dump();
  const json unknown = post("/api/v1/integrate", std::string(kChain) + R"(,"chain":{"k":1}})", 400);
  EXPECT_EQ(unknown["error"]["field"], "chain.k") << unknown.dump();
}

}  // namespace
}  // namespace lienewton::service
