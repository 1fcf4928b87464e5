// Adaptive steps over HTTP: integrate with rtol/atol answers and streams its accepted steps with their sizes and
// error estimates, bad tolerances are a 422 naming the field, and work-precision runs against tolerance.
#include <gtest/gtest.h>

#include <cmath>

#include "server/json_codec.hpp"
#include "test_server.hpp"

namespace lienewton::service {
namespace {

using testing::post_lines;

class AdaptiveRoutes : public testing::SharedServerTest {};

TEST_F(AdaptiveRoutes, IntegrateChoosesItsStepsAndStreamsThem) {
  auto c = client();
  const std::string body =
      R"({"problem":"rigid-body","integrator":"rkmk-gauss2","t_end":2,"h":2,"rtol":1e-8,"atol":1e-8})";
  auto res = c.Post("/api/v1/integrate", body, "application/json");
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200) << res->body;
  const json r = json::parse(res->body);
  EXPECT_EQ(r["status"], "converged");
  EXPECT_EQ(r["adaptive"], true);
  EXPECT_LT(r["global_error"].get<double>(), 1e-6);
  int rejected = 0;
  double t = 0;
  for (const json& s : r["steps"]) {
    EXPECT_NEAR(s["t"].get<double>(), t + s["h"].get<double>(), 1e-12);
    EXPECT_LE(s["error_estimate"].get<double>(), 1.0);
    rejected += s["rejected"].get<int>();
    t = s["t"].get<double>();
  }
  EXPECT_EQ(t, 2.0);
  EXPECT_GT(r["rejected"].get<int>(), 0);  // h = t_end is far too long a first step at 1e-8
  EXPECT_EQ(r["rejected"].get<int>(), rejected);

  std::vector<json> records;
  post_lines(c, "/api/v1/integrate", body, "application/x-ndjson", [&](const std::string& line) {
    records.push_back(json::parse(line));
    return true;
  });
  ASSERT_EQ(records.size(), r["steps"].size() + 1);
  EXPECT_EQ(records.front()["type"], "step");
  EXPECT_EQ(records.front()["h"], r["steps"][0]["h"]);
  EXPECT_EQ(records.front()["error_estimate"], r["steps"][0]["error_estimate"]);
  EXPECT_EQ(records.back()["type"], "result");

  auto fixed = c.Post("/api/v1/integrate", R"({"problem":"rigid-body","h":0.5,"t_end":1})", "application/json");
  ASSERT_TRUE(fixed);
  const json f = json::parse(fixed->body);
  EXPECT_EQ(f["adaptive"], false);
  EXPECT_EQ(f["steps"][0]["h"], 0.5);
  EXPECT_TRUE(f["steps"][0]["error_estimate"].is_null());
}

TEST_F(AdaptiveRoutes, BadTolerancesAre422NamingTheField) {
  auto c = client();
  for (const char* field : {"rtol", "atol"}) {
    for (const char* bad : {"0", "-1e-6", "2"}) {
      auto res = c.Post("/api/v1/integrate", std::string(R"({"problem":"rigid-body",")") + field + "\":" + bad + "}",
                        "application/json");
      ASSERT_TRUE(res);
      EXPECT_EQ(res->status, 422) << field << " " << bad << ": " << res->body;
      EXPECT_EQ(json::parse(res->body)["error"]["field"], field) << res->body;
    }
  }
  auto wp = c.Post("/api/v1/work-precision", R"({"choices":[{"integrator":"rkmk4"}],"tolerances":[1e-3,0]})",
                   "application/json");
  ASSERT_TRUE(wp);
  EXPECT_EQ(wp->status, 422) << wp->body;
  EXPECT_EQ(json::parse(wp->body)["error"]["field"], "tolerances");
}

TEST_F(AdaptiveRoutes, WorkPrecisionAgainstTolerance) {
  auto c = client();
  auto res = c.Post("/api/v1/work-precision",
                    R"({"problem":"rigid-body","t_end":1,"choices":[{"integrator":"rkmk4"}],"tolerances":[1e-4,1e-7]})",
                    "application/json");
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200) << res->body;
  const json points = json::parse(res->body)["series"][0]["points"];
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[0]["tolerance"], 1e-4);
  EXPECT_EQ(points[1]["tolerance"], 1e-7);
  EXPECT_LT(points[1]["error"].get<double>(), points[0]["error"].get<double>());
  auto png = c.Post("/api/v1/render/work-precision",
                    R"({"problem":"rigid-body","t_end":1,"choices":[{"integrator":"rkmk4"}],"tolerances":[1e-4,1e-7]})",
                    "application/json");
  ASSERT_TRUE(png);
  EXPECT_EQ(png->status, 200);
  EXPECT_EQ(png->get_header_value("Content-Type"), "image/png");
}

}  // namespace
}  // namespace lienewton::service
