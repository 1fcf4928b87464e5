// /openapi.json describes exactly the routes the server registers, and every documented route answers.
#include <gtest/gtest.h>

#include <set>

#include "core/status.hpp"
#include "render/colormap.hpp"
#include "render/series_style.hpp"
#include "server/json_codec.hpp"
#include "server/routes.hpp"
#include "test_server.hpp"

namespace lienewton::service {
namespace {

TEST(OpenApi, DocumentMatchesTheRegisteredRoutes) {
  testing::TestServer s;
  auto c = s.client();
  auto res = c.Get("/openapi.json");
  ASSERT_TRUE(res);
  const json doc = json::parse(res->body);
  std::set<std::pair<std::string, std::string>> documented;
  for (const auto& [path, ops] : doc["paths"].items()) {
    for (const auto& [method, op] : ops.items()) {
      std::string upper = method;
      for (auto& ch : upper) ch = static_cast<char>(ch - 'a' + 'A');
      documented.emplace(upper, path);
      EXPECT_TRUE(op.contains("responses")) << path;
      EXPECT_TRUE(op["responses"].contains("200")) << path;
    }
  }
  const auto& reg = s.server->registered_routes();
  const std::set<std::pair<std::string, std::string>> registered(reg.begin(), reg.end());
  EXPECT_EQ(documented, registered);
  // The contract's paths are all there.
  for (const char* path : {"/api/v1/solve", "/api/v1/solve/events", "/api/v1/sweep", "/api/v1/integrate",
                           "/api/v1/work-precision", "/api/v1/render/frames", "/api/v1/render/heatmap", "/livez",
                           "/readyz", "/metrics", "/openapi.json", "/"}) {
    EXPECT_TRUE(doc["paths"].contains(path)) << path;
  }
  // Every $ref resolves.
  const std::string text = doc.dump();
  std::size_t at = 0;
  while ((at = text.find("#/components/schemas/", at)) != std::string::npos) {
    at += 21;
    const std::string name = text.substr(at, text.find('"', at) - at);
    EXPECT_TRUE(doc["components"]["schemas"].contains(name)) << name;
  }
  // Every documented route is really served: a quick (invalid) request may be refused, but never 404/405.
  for (const auto& [method, path] : documented) {
    auto r = method == "GET" ? c.Get(path + "?tol=-1") : c.Post(path, R"({"tol":-1})", "application/json");
    ASSERT_TRUE(r) << method << " " << path;
    EXPECT_NE(r->status, 404) << method << " " << path;
    EXPECT_NE(r->status, 405) << method << " " << path;
  }
}

TEST(OpenApi, RequestSchemasListTheCodecFields) {
  const json doc = json::parse(openapi_document());
  const json& solve = doc["components"]["schemas"]["SolveRequest"]["properties"];
  for (const char* f : {"problem", "n", "h", "method", "differential", "tol", "max_iterations", "seed", "z",
                        "include_iterates", "rigid_body"}) {
    EXPECT_TRUE(solve.contains(f)) << f;
  }
  const json& sweep = doc["components"]["schemas"]["SweepRequest"]["properties"];
  for (const char* f : {"problem", "methods", "differential", "n", "h", "seed", "tol", "max_iterations"}) {
    EXPECT_TRUE(sweep.contains(f)) << f;
  }
}

std::string css(render::Color c) {
  return "rgb(" + std::to_string(c.r) + "," + std::to_string(c.g) + "," + std::to_string(c.b) + ")";
}

// The dashboard reads its words and colours from "x-lienewton": every value the API accepts or answers has a
// label, a short label and a description, every status a colour, and the colours are the renderer's.
TEST(OpenApi, ExtensionLabelsEveryEnumValue) {
  const json doc = json::parse(openapi_document());
  const json& schemas = doc["components"]["schemas"];
  const json& ext = doc["x-lienewton"];
  const std::pair<const char*, json> published[] = {
      {"problem", schemas["SolveRequest"]["properties"]["problem"]["enum"]},
      {"method", schemas["SolveRequest"]["properties"]["method"]["enum"]},
      {"differential", schemas["SolveRequest"]["properties"]["differential"]["enum"]},
      {"linear_solver", schemas["SolveRequest"]["properties"]["linear_solver"]["enum"]},
      {"integrator", schemas["IntegrateRequest"]["properties"]["integrator"]["enum"]},
      {"status", schemas["SolveResult"]["properties"]["status"]["enum"]},
      {"heatmap_metric", schemas["RenderHeatmapRequest"]["properties"]["metric"]["enum"]},
  };
  for (const auto& [name, values] : published) {
    ASSERT_TRUE(values.is_array() && !values.empty()) << name;
    const json& entries = ext["enums"][name];
    ASSERT_EQ(entries.size(), values.size()) << name;
    std::set<std::string> labels;
    for (std::size_t i = 0; i < values.size(); ++i) {
      EXPECT_EQ(entries[i]["value"], values[i]) << name;  // same values, same order as the schema
      for (const char* key : {"label", "short", "description"}) {
        EXPECT_FALSE(entries[i].value(key, std::string()).empty()) << name << " " << values[i] << " " << key;
      }
      EXPECT_TRUE(labels.insert(entries[i]["label"].get<std::string>()).second) << name << ": label used twice";
    }
  }
  // The charts' series styles, as the renderer draws them.
  ASSERT_EQ(ext["series_styles"].size(), render::kDistinctSeriesStyles);
  for (std::size_t i = 0; i < render::kDistinctSeriesStyles; ++i) {
    const render::SeriesStyle s = render::series_style(i);
    EXPECT_EQ(ext["series_styles"][i]["color"], css(s.color)) << i;
    EXPECT_EQ(ext["series_styles"][i]["marker"], std::string(to_string(s.marker))) << i;
    EXPECT_EQ(ext["series_styles"][i]["dash"], std::string(to_string(s.dash))) << i;
  }
  for (const auto& entry : ext["enums"]["method"]) {
    EXPECT_EQ(entry["uses_differential"], entry["value"] != "fixed-point") << entry["value"];
  }
  for (const auto& entry : ext["enums"]["status"]) {
    const auto status = status_from_string(entry["value"].get<std::string>());
    ASSERT_TRUE(status) << entry["value"];
    if (*status != Status::converged) EXPECT_EQ(entry["color"], css(render::status_color(*status))) << entry["value"];
    else EXPECT_EQ(entry["color"], "rgb(27,120,55)");
  }
  EXPECT_EQ(ext["colors"]["no_value"], css(render::kNoValueColor));
  const json& stops = ext["colors"]["viridis"];
  ASSERT_EQ(stops.size(), 256u);
  for (std::size_t i : {std::size_t{0}, std::size_t{100}, std::size_t{255}}) {
    const render::Color c = render::viridis(static_cast<double>(i) / 255.0);
    EXPECT_EQ(stops[i], json::array({c.r, c.g, c.b})) << i;
  }
}

}  // namespace
}  // namespace lienewton::service
