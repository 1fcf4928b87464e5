// /openapi.json describes exactly the routes the server registers, and every documented route answers.
#include <gtest/gtest.h>

#include <set>

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

}  // namespace
}  // namespace lienewton::service
