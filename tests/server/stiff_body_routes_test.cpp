// The built-in stiff body over HTTP: POST /api/v1/integrate with "problem": "stiff-body" on "group": "SOxR" and its
// parameters as the stiff_body object converges to scipy's state at t = 1 (stiff_body_reference_values.hpp) and
// reports no invariants; the catalog names its group and no invariants; bad parameters are 422 naming the field.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <string>

#include "core/so3xr3_state.hpp"
#include "core/stiff_body_params.hpp"
#include "test_server.hpp"
#include "tests/core/stiff_body_reference_values.hpp"

namespace lienewton::service {
namespace {

class StiffBodyRoutes : public testing::SharedServerTest {};
using testing::matrix_from_rows;

constexpr const char* kBody = R"({"problem":"stiff-body","group":"SOxR","integrator":"rkmk-radau3","h":0.00390625)";

// Every parameter given, at the defaults: R(0) as rows.
std::string all_parameters() {
  const StiffBodyParams p;
  json rotation = json::array();
  for (int i = 0; i < 3; ++i) rotation.push_back({p.rotation(i, 0), p.rotation(i, 1), p.rotation(i, 2)});
  return json{{"k", 1e4}, {"c", 1e4}, {"J", {1, 2, 3}}, {"f", {0.5, 0.3, 0.2}},
              {"rotation", rotation}, {"omega", {1, -2, 0.5}}}.dump();
}

// The default body at t = 1 (k = c = 1e4): rkmk-radau3 at h = 2^-8 is within 1e-7 of scipy's Radau (6.7e-9 when
// written; StiffBody.DefaultBodyMatchesScipyRadauAndDop853 in the core tests says why not closer). c absent is c = k.
TEST_F(StiffBodyRoutes, IntegrateConvergesToScipysStateWithNoInvariants) {
  const json r = post("/api/v1/integrate", std::string(kBody) + R"(,"stiff_body":)" + all_parameters() + "}");
  ASSERT_EQ(r["status"], "converged") << r.dump().substr(0, 500);
  ASSERT_EQ(r["steps"].size(), 256u);
  const test::StiffBodyCase& scipy = test::kStiffBodyCases[0];
  ASSERT_EQ(scipy.k, 1e4);
  const Eigen::MatrixXd expected =
      so3xr3::state(Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(scipy.rotation),
                    Eigen::Map<const Eigen::Vector3d>(scipy.omega));
  const Eigen::MatrixXd y = matrix_from_rows(r["y"]);
  EXPECT_LE((y - expected).norm(), 1e-7);
  EXPECT_LE(r["global_error"].get<double>(), 1e-7) << "against the service's own reference solution";
  for (const char* invariant : {"energy", "vertical_momentum", "axial_spin"}) {
    EXPECT_TRUE(r[std::string(invariant) + "_drift"].is_null()) << invariant;
    EXPECT_TRUE(r["steps"][0][invariant].is_null()) << invariant;
  }
  const json defaults = post("/api/v1/integrate", std::string(kBody) + R"(,"stiff_body":{"k":1e4}})");
  EXPECT_EQ(matrix_from_rows(defaults["y"]), y) << "absent parameters keep their defaults, c = k";
  // Parameters that change the body change its run.
  const json unforced = post("/api/v1/integrate", std::string(kBody) + R"(,"stiff_body":{"f":[0,0,0]}})");
  ASSERT_EQ(unforced["status"], "converged");
  EXPECT_GT((matrix_from_rows(unforced["y"]) - y).norm(), 1e-6);
  // It has no invariants to draw.
  const json none = post("/api/v1/render/invariants", std::string(kBody) + R"(,"t_end":0.0625})", 422);
  EXPECT_EQ(none["error"]["field"], "problem") << none.dump();
}

TEST_F(StiffBodyRoutes, TheCatalogNamesItsGroupAndNoInvariants) {
  auto res = client().Get("/openapi.json");
  ASSERT_TRUE(res);
  const json doc = json::parse(res->body);
  json body;
  for (const json& p : doc["x-lienewton"]["enums"]["problem"])
    if (p["value"] == "stiff-body") body = p;
  EXPECT_EQ(body["group"], "SOxR");
  EXPECT_EQ(body["n"], 3);
  EXPECT_EQ(body["invariants"], json::array());
  const json& schema = doc["components"]["schemas"]["StiffBody"]["properties"];
  EXPECT_EQ(schema["k"]["default"], 1e4);
  EXPECT_FALSE(schema["c"].contains("default")) << "absent: c = k";
  for (const char* name : {"J", "f", "rotation", "omega"}) EXPECT_TRUE(schema.contains(name)) << name;
}

TEST_F(StiffBodyRoutes, BadParametersAre422NamingTheField) {
  expect_422_naming("/api/v1/integrate", kBody, {
      {R"(,"stiff_body":{"k":-1}})", "stiff_body.k"},
      {R"(,"stiff_body":{"c":-1}})", "stiff_body.c"},
      {R"(,"stiff_body":{"J":[1,0,3]}})", "stiff_body.J"},
      {R"(,"stiff_body":{"f":[0,2e9,0]}})", "stiff_body.f"},
      {R"(,"stiff_body":{"rotation":[[1,0,0],[0,1,0],[0,0.5,1]]}})", "stiff_body.rotation"},
      {R"(,"stiff_body":{"rotation":[[1,0,0],[0,1,0],[0,0,-1]]}})", "stiff_body.rotation"},
      {R"(,"z":[[1,0,0,0,0,0,0],[0,1,0,0,0,0,0],[0,0,1,0,0,0,0],[0,0,0,1,0,0,0],[0,0,0,0,1,0,0],[0,0,0,0,0,1,0],[0,0,0,0,0,0,1]]})", "z"},
  });
  const json so = post("/api/v1/integrate", R"({"problem":"stiff-body","group":"SO","h":0.1})", 422);
  EXPECT_EQ(so["error"]["field"], "group") << so.dump();
  const json implied = post("/api/v1/integrate", R"({"problem":"stiff-body","h":0.0625,"t_end":0.25})");
  EXPECT_EQ(implied["status"], "converged") << implied.dump().substr(0, 300) << ": its group SOxR is implied";
  // Not a number, or a name the object does not have: 400 naming it.
  const json text = post("/api/v1/integrate", std::string(kBody) + R"(,"stiff_body":{"k":"stiff"}})", 400);
  EXPECT_EQ(text["error"]["field"], "stiff_body.k") << text.dump();
  const json unknown = post("/api/v1/integrate", std::string(kBody) + R"(,"stiff_body":{"mass":1}})", 400);
  EXPECT_EQ(unknown["error"]["field"], "stiff_body.mass") << unknown.dump();
}

}  // namespace
}  // namespace lienewton::service
