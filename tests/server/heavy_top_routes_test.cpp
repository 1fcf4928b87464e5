// The built-in heavy top over HTTP: POST /api/v1/integrate with "problem": "heavy-top" on "group": "SOxR" answers
// its state, every step's energy and vertical momentum and their drifts (equal to those evaluated here from the
// returned y), streams the same per step, work-precision reports the drifts per point, render/frames draws the
// top's body axes and render/invariants its drifts over time, and bad parameters are 422 naming the field.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <string>

#include "core/integrators/methods.hpp"
#include "core/heavy_top_params.hpp"
#include "core/vocabulary.hpp"
#include "server/json_codec.hpp"
#include "test_server.hpp"
#include "tests/core/heavy_top_field.hpp"

namespace lienewton::service {
namespace {

class HeavyTopRoutes : public testing::SharedServerTest {};
using testing::matrix_from_rows;

double energy(const Eigen::MatrixXd& y) { return test::heavy_top_energy(y.topLeftCorner(3, 3), y.block(3, 6, 3, 1)); }
double momentum(const Eigen::MatrixXd& y) {
  return test::heavy_top_vertical_momentum(y.topLeftCorner(3, 3), y.block(3, 6, 3, 1));
}

constexpr const char* kTop = R"({"problem":"heavy-top","group":"SOxR","integrator":"dirk-cg2","h":0.0078125,"t_end":0.125)";

TEST_F(HeavyTopRoutes, IntegrateReportsTheInvariantsOfTheReturnedStates) {
  const json r = post("/api/v1/integrate", std::string(kTop) + R"(,"frames":16})");
  ASSERT_EQ(r["status"], "converged") << r.dump();
  ASSERT_EQ(r["steps"].size(), 16u);
  ASSERT_EQ(r["frames"].size(), 17u);
  const double e0 = energy(matrix_from_rows(r["frames"][0])), l0 = momentum(matrix_from_rows(r["frames"][0]));
  // The drifts' scales: the kinetic plus potential energy's size and the whole angular momentum |J w(0)|.
  const Eigen::Vector3d jw0 = test::kHeavyTopInertia.cwiseProduct(test::kHeavyTopOmega0);
  const double e_scale = 0.5 * test::kHeavyTopOmega0.dot(jw0) + 15.0 * 9.81, l_scale = jw0.norm();
  EXPECT_NEAR(r["energy_scale"].get<double>(), e_scale, 1e-12 * e_scale);
  EXPECT_NEAR(r["vertical_momentum_scale"].get<double>(), l_scale, 1e-12 * l_scale);
  // The Lagrange top's spin about its axis, body omega_y = 150, is kept by every step to rounding.
  EXPECT_EQ(r["initial_axial_spin"].get<double>(), 150.0);
  EXPECT_LE(r["axial_spin_drift"].get<double>(), 1e-13);
  EXPECT_NEAR(r["initial_energy"].get<double>(), e0, 1e-12 * std::abs(e0));
  EXPECT_NEAR(r["initial_vertical_momentum"].get<double>(), l0, 1e-12 * std::abs(l0));
  double de = 0, dl = 0;
  for (std::size_t k = 1; k < r["frames"].size(); ++k) {
    const Eigen::MatrixXd y = matrix_from_rows(r["frames"][k]);
    EXPECT_NEAR(r["steps"][k - 1]["energy"].get<double>(), energy(y), 1e-12 * std::abs(e0));
    EXPECT_NEAR(r["steps"][k - 1]["vertical_momentum"].get<double>(), momentum(y), 1e-12 * std::abs(l0));
    de = std::max(de, std::abs(energy(y) - e0) / e_scale);
    dl = std::max(dl, std::abs(momentum(y) - l0) / l_scale);
  }
  EXPECT_NEAR(r["energy_drift"].get<double>(), de, 1e-12 + 1e-9 * de);
  EXPECT_NEAR(r["vertical_momentum_drift"].get<double>(), dl, 1e-12 + 1e-9 * dl);
  EXPECT_EQ(matrix_from_rows(r["y"]), matrix_from_rows(r["frames"][16]));
  EXPECT_GT(r["global_error"].get<double>(), 0.0);  // against the reference solution on SOxR

  // A problem without them reports null.
  const json rigid = post("/api/v1/integrate", R"({"problem":"rigid-body","h":0.25,"t_end":0.5})");
  EXPECT_TRUE(rigid["vertical_momentum_drift"].is_null());
  EXPECT_TRUE(rigid["steps"][0]["vertical_momentum"].is_null());
  EXPECT_TRUE(rigid["energy_drift"].is_number());
}

TEST_F(HeavyTopRoutes, StreamsWorkPrecisionAndFramesCarryTheTop) {
  auto c = client();
  int steps = 0;
  bool result = false;
  testing::post_lines(c, "/api/v1/integrate", std::string(kTop) + "}", "application/x-ndjson", [&](const std::string& line) {
    const json record = json::parse(line);
    if (record["type"] == "step") {
      ++steps;
      EXPECT_TRUE(record["energy"].is_number() && record["vertical_momentum"].is_number()) << line;
    }
    if (record["type"] == "result") result = record["vertical_momentum_drift"].is_number();
    return true;
  });
  EXPECT_EQ(steps, 16);
  EXPECT_TRUE(result);

  const json wp = post("/api/v1/work-precision", R"({"problem":"heavy-top","group":"SOxR","t_end":0.0625,)"
                                                  R"("h":[0.0078125,0.00390625],"choices":[{"integrator":"dirk-cg2"}]})");
  for (const json& p : wp["series"][0]["points"]) {
    EXPECT_EQ(p["status"], "converged");
    EXPECT_GT(p["energy_drift"].get<double>(), 0.0);
    EXPECT_GT(p["vertical_momentum_drift"].get<double>(), 0.0);
  }

  auto png = c.Post("/api/v1/render/frames", std::string(kTop) + R"(,"frames":4,"width":96,"height":96})",
                    "application/json");
  ASSERT_TRUE(png);
  EXPECT_EQ(png->status, 200) << png->body;
  EXPECT_EQ(png->body.substr(1, 3), "PNG");
  auto drift = c.Post("/api/v1/render/invariants", std::string(kTop) + R"(,"width":320,"height":240})", "application/json");
  ASSERT_TRUE(drift);
  EXPECT_EQ(drift->status, 200) << drift->body;
  EXPECT_EQ(drift->body.substr(1, 3), "PNG");
  const json none_to_draw = post("/api/v1/render/invariants", R"({"problem":"paper-linear","h":0.25,"t_end":0.5})", 422);
  EXPECT_EQ(none_to_draw["error"]["field"], "problem") << none_to_draw.dump();
  // A group without a rotation part is refused by name.
  auto none = c.Post("/api/v1/render/frames", R"({"group":"Rnxn","problem":"paper-linear","h":0.1,"t_end":0.2})",
                     "application/json");
  ASSERT_TRUE(none);
  EXPECT_EQ(none->status, 422) << none->body;
}

// The dashboard reads a problem's group and invariants from the catalog, and the invariants' words from its enum.
TEST_F(HeavyTopRoutes, TheCatalogNamesTheTopsGroupAndInvariants) {
  auto res = client().Get("/openapi.json");
  ASSERT_TRUE(res);
  const json doc = json::parse(res->body);
  json top;
  for (const json& p : doc["x-lienewton"]["enums"]["problem"])
    if (p["value"] == "heavy-top") top = p;
  EXPECT_EQ(top["group"], "SOxR");
  EXPECT_EQ(top["n"], 3);
  EXPECT_EQ(top["invariants"], json::array({"energy", "vertical_momentum", "axial_spin"}));
  EXPECT_EQ(doc["x-lienewton"]["enums"]["invariant"].size(), 3u);
  const json& heavy = doc["components"]["schemas"]["HeavyTop"]["properties"];
  EXPECT_EQ(heavy["mass"]["default"], 15.0);
  EXPECT_EQ(heavy["mass"]["minimum"], 0.0);
  EXPECT_TRUE(doc["components"]["schemas"]["IntegrateResult"]["properties"].contains("vertical_momentum_drift"));
}

// The defaults of the routes that sweep or time the top: the stability map sweeps h alone at the top's n = 3
// (no "n must be 3, got 2"), and work-precision without choices or h runs every integrator at steps from the top's
// time scale, each order nominal within 0.2 or null with its reason.
TEST_F(HeavyTopRoutes, DefaultsComeFromTheTop) {
  const json map = post("/api/v1/sweep", R"({"problem":"heavy-top","group":"SOxR","h":[0.25,1]})");
  ASSERT_EQ(map["cells"].size(), 6u) << map.dump();
  for (const json& cell : map["cells"]) EXPECT_EQ(cell["n"], 3);
  const json wp = post("/api/v1/work-precision", R"({"problem":"heavy-top","group":"SOxR","t_end":0.015625})");
  ASSERT_EQ(wp["series"].size(), std::size(kAllIntegrators));
  for (const json& s : wp["series"]) {
    ASSERT_EQ(s["points"].size(), 6u) << "at t_end = 2^-6 the runs are short enough for all six";
    EXPECT_EQ(s["points"][0]["h"], 0.0009765625) << "2^-10: h |omega| = 0.15, h rho <= 1";
    if (s["fitted_order"].is_null()) {
      EXPECT_FALSE(s["fit_reason"].get<std::string>().empty()) << s.dump();
    } else {
      const std::string integrator = s["choice"]["integrator"];
      const int nominal = order_of(*from_api_name(kAllIntegrators, integrator));
      EXPECT_NEAR(s["fitted_order"].get<double>(), nominal, 0.2) << integrator;
    }
  }
  // The POST picture without choices takes the same defaults as the GET one.
  auto png = client().Post("/api/v1/render/work-precision",
                           R"({"problem":"rigid-body","t_end":0.25,"h":[0.0625,0.03125],"width":320,"height":240})",
                           "application/json");
  ASSERT_TRUE(png);
  EXPECT_EQ(png->status, 200) << png->body;
  EXPECT_EQ(png->body.substr(1, 3), "PNG");
}

TEST_F(HeavyTopRoutes, BadParametersAre422NamingTheField) {
  expect_422_naming("/api/v1/integrate", kTop, {
      {R"(,"heavy_top":{"mass":-1}})", "heavy_top.mass"},
      {R"(,"heavy_top":{"inertia":[1,0,1]}})", "heavy_top.inertia"},
      {R"(,"heavy_top":{"rotation":[[1,0,0],[0,1,0],[0,0.5,1]]}})", "heavy_top.rotation"},
      {R"(,"heavy_top":{"omega":[0,1e7,0]}})", "heavy_top.omega"},
      {R"(,"z":[[1,0,0,0,0,0,0],[0,1,0,0,0,0,0],[0,0,1,0,0,0,0],[0,0,0,1,0,0,0],[0,0,0,0,1,0,0],[0,0,0,0,0,1,0],[0,0,0,0,0,0,1]]})", "z"},
  });
  // The top's group is implied when the request names none, and another one is refused naming the one it needs.
  const json so = post("/api/v1/integrate", R"({"problem":"heavy-top","group":"SO","h":0.1})", 422);
  EXPECT_EQ(so["error"]["field"], "group") << so.dump();
  EXPECT_NE(so["error"]["message"].get<std::string>().find("SOxR"), std::string::npos) << so.dump();
  const json implied = post("/api/v1/integrate", R"({"problem":"heavy-top","h":0.0078125,"t_end":0.0625})");
  EXPECT_EQ(implied["status"], "converged") << implied.dump().substr(0, 300);
  EXPECT_EQ(matrix_from_rows(implied["y"]).rows(), 7);
  // Parameters that change the top change its run: a lighter top has less potential energy to trade.
  const json light = post("/api/v1/integrate", std::string(kTop) + R"(,"heavy_top":{"mass":1,"gravity":[0,0,-1]}})");
  ASSERT_EQ(light["status"], "converged");
  const Eigen::MatrixXd y = matrix_from_rows(light["y"]);
  HeavyTopParams p;
  p.mass = 1;
  p.gravity = {0, 0, -1};
  const Eigen::Vector3d w = y.block(3, 6, 3, 1);
  // About the pivot: the parallel-axis shift m (|chi|^2 I - chi chi^T) of chi = e_y adds m to the x and z moments.
  const Eigen::Vector3d j = p.inertia + p.mass * Eigen::Vector3d(1, 0, 1);
  const double e = 0.5 * w.dot(j.cwiseProduct(w)) - p.mass * p.gravity.dot(y.topLeftCorner(3, 3) * p.center);
  EXPECT_NEAR(light["steps"].back()["energy"].get<double>(), e, 1e-12 * std::abs(e));
}

}  // namespace
}  // namespace lienewton::service
