// /openapi.json describes exactly the routes the server registers, and every documented route answers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>

#include "core/basins.hpp"
#include "core/fields.hpp"
#include "core/integrate.hpp"
#include "core/solve.hpp"
#include "core/sweep.hpp"
#include "core/work_precision.hpp"
#include "core/solvers/newton_step.hpp"
#include "core/solvers/watchdog.hpp"
#include "core/status.hpp"
#include "core/validation.hpp"
#include "render/colormap.hpp"
#include "render/series_style.hpp"
#include "server/json_codec.hpp"
#include "server/render_requests.hpp"
#include "server/routes.hpp"
#include "server/server_options.hpp"
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

// A generated client calls routes by stable names under three tags, and the version the document states is the one
// the server answers on /api/v1/version.
TEST(OpenApi, OperationsHaveStableNamesTagsAndTheVersion) {
  testing::TestServer s;
  auto c = s.client();
  const json doc = json::parse(c.Get("/openapi.json")->body);
  std::set<std::string> ids, tags;
  for (const auto& [path, ops] : doc["paths"].items())
    for (const auto& [method, op] : ops.items()) {
      EXPECT_TRUE(ids.insert(op["operationId"].get<std::string>()).second) << op["operationId"];
      ASSERT_EQ(op["tags"].size(), 1u) << method << " " << path;
      tags.insert(op["tags"][0].get<std::string>());
    }
  for (const char* id : {"solve", "solveEvents", "sweep", "basins", "integrate", "workPrecision", "renderFrames",
                         "renderFramesGet", "livez", "openapi", "version", "dashboard"})
    EXPECT_TRUE(ids.count(id)) << id;
  EXPECT_EQ(tags, (std::set<std::string>{"compute", "render", "service"}));
  const auto version = c.Get("/api/v1/version");
  ASSERT_TRUE(version);
  ASSERT_EQ(version->status, 200);
  const json v = json::parse(version->body);
  EXPECT_EQ(v["version"], doc["info"]["version"]);
  EXPECT_EQ(v["version"], LIENEWTON_VERSION);
  EXPECT_FALSE(v["build"].get<std::string>().empty());
  EXPECT_TRUE(doc["components"]["schemas"]["ErrorDetail"]["properties"].contains("line"));
}

// A client plans with the running server's caps (its flags), not the defaults: the basin size they allow for
// k methods, floor(sqrt(max_values / (basin_pixel_values k))), is accepted and one more is refused.
TEST(OpenApi, PublishesTheRunningServersLimits) {
  ServerOptions options;
  options.output.max_values = 30'000;
  options.limits.max_grid_cells = 777;
  options.request_timeout = 11;
  options.sweep_timeout = 13;
  testing::TestServer s(options);
  auto c = s.client();
  auto res = c.Get("/openapi.json");
  ASSERT_TRUE(res);
  const json limits = json::parse(res->body)["x-lienewton"]["output_limits"];
  EXPECT_EQ(limits["max_values"], 30'000);
  EXPECT_EQ(limits["max_grid_cells"], 777);
  EXPECT_EQ(limits["max_image_pixels"], OutputLimits{}.max_image_pixels);
  EXPECT_EQ(limits["request_seconds"], 11.0);
  EXPECT_EQ(limits["sweep_seconds"], 13.0);
  const double per_pixel = limits["basin_pixel_values"].get<double>() * 2;  // two methods
  const int largest = static_cast<int>(std::floor(std::sqrt(30'000 / per_pixel)));
  const auto basin = [&](int size) {
    const json body{{"size", size}, {"methods", {"newton-group", "newton-algebra"}}, {"max_iterations", 1}};
    return c.Post("/api/v1/basins", body.dump(), "application/json");
  };
  auto over = basin(largest + 1);
  ASSERT_TRUE(over);
  EXPECT_EQ(over->status, 413) << over->body;
  auto at = basin(largest);
  ASSERT_TRUE(at);
  EXPECT_EQ(at->status, 200) << at->body;
}

// The output cap counts each iterate as the group's matrix: 4 x 4 on SE(3), where n = 3 (n x n would let 81
// iterates of 16 numbers, 1296, under a cap of 1000).
TEST(OpenApi, IteratesCountTheGroupsMatrixSize) {
  ServerOptions options;
  options.output.max_values = 1000;
  testing::TestServer s(options);
  auto c = s.client();
  const json se3{{"group", "SE"}, {"h", 0.5}, {"include_iterates", true}, {"max_iterations", 80},
                 {"g", "w = [0.6; 0.8; 0.5]; g = [0 -w(3) w(2) 1; w(3) 0 -w(1) 0; -w(2) w(1) 0 0; 0 0 0 0]"}};
  auto over = c.Post("/api/v1/solve", se3.dump(), "application/json");
  ASSERT_TRUE(over);
  EXPECT_EQ(over->status, 413) << over->body;
  EXPECT_EQ(json::parse(over->body)["error"]["field"], "include_iterates") << over->body;
  json so3 = se3;
  so3.erase("group");
  so3["g"] = "w = [0.6; 0.8; 0.5]; g = [0 -w(3) w(2); w(3) 0 -w(1); -w(2) w(1) 0]";
  auto at = c.Post("/api/v1/solve", so3.dump(), "application/json");  // 81 x 9 = 729 numbers
  ASSERT_TRUE(at);
  EXPECT_EQ(at->status, 200) << at->body;
}

// The output cap counts what an integration's answer holds: every value of its step records (null ones too)
// and its states (y, and the frames: y(0), every stride-th step and the last, which 5 steps show with 2 and 3
// frames). A cap of exactly that count is met and one fewer is refused.
TEST(OpenApi, IntegrationCapCountsTheSerialisedAnswer) {
  // Every scalar in j, null ones too; an object's keys are names, not values.
  const std::function<std::size_t(const json&)> values_in = [&](const json& j) {
    if (!j.is_structured()) return std::size_t{1};
    std::size_t count = 0;
    for (const json& v : j) count += values_in(v);
    return count;
  };
  for (const int frames : {0, 2, 3}) {
    const json body{{"problem", "rigid-body"}, {"h", 0.2}, {"t_end", 1}, {"frames", frames}};
    testing::TestServer roomy;
    auto c = roomy.client();
    auto res = c.Post("/api/v1/integrate", body.dump(), "application/json");
    ASSERT_TRUE(res);
    ASSERT_EQ(res->status, 200) << res->body;
    const json answer = json::parse(res->body);
    ASSERT_EQ(answer["steps"].size(), 5u);
    const std::size_t held = values_in(answer["steps"]) + values_in(answer["y"]) + values_in(answer["frames"]);
    for (const std::size_t cap : {held, held - 1}) {
      ServerOptions options;
      options.output.max_values = cap;
      testing::TestServer s(options);
      auto capped = s.client().Post("/api/v1/integrate", body.dump(), "application/json");
      ASSERT_TRUE(capped);
      EXPECT_EQ(capped->status, cap == held ? 200 : 413) << "frames " << frames << ", cap " << cap << ": " << capped->body;
    }
  }
}

TEST(OpenApi, RequestSchemasListTheCodecFields) {
  const json doc = json::parse(openapi_document(ServerOptions{}));
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

// Each bounded field has one row in core/fields.hpp: the schema shows the row's bounds, the codec refuses the
// first value beyond each bound with the row's message, and core validation refuses it with the same message.
TEST(OpenApi, FieldTableBoundsAreTheSchemaTheCodecAndTheCore) {
  const json doc = json::parse(openapi_document(ServerOptions{}));
  const json& solve = doc["components"]["schemas"]["SolveRequest"]["properties"];
  const json& integrate = doc["components"]["schemas"]["IntegrateRequest"]["properties"];
  const Limits limits = Limits::unlimited();
  auto codec_error = [&](const std::string& name, const json& value) -> std::string {
    json body = {{name, value}};
    if (name == "t_end") body["h"] = 1e-3;  // keep h <= t_end out of the way
    try {
      name == "t_end" ? (void)integrate_request_from_json(body, limits) : (void)solve_request_from_json(body, limits);
    } catch (const FieldError& e) {
      EXPECT_EQ(e.field(), name);
      return e.what();
    }
    return "accepted";
  };
  for (const fields::NumberField* f : fields::kNumberFields) {
    const json& schema = (std::string(f->name) == "t_end" ? integrate : solve)[f->name];
    EXPECT_EQ(schema["minimum"].get<double>(), f->min) << f->name;
    EXPECT_EQ(schema["maximum"].get<double>(), f->max) << f->name;
    EXPECT_EQ(schema.value("exclusiveMinimum", false), f->min_exclusive) << f->name;
    const double below = f->min_exclusive ? f->min : std::nextafter(f->min, -1.0);
    const double above = std::nextafter(f->max, 2 * f->max);
    for (double bad : {below, above}) {
      EXPECT_EQ(codec_error(f->name, bad), f->message(f->name)) << f->name << " " << bad;
      try {
        validation::check(*f, bad, f->name);
        ADD_FAILURE() << f->name << " " << bad << " passed core validation";
      } catch (const RequestError& e) {
        EXPECT_EQ(std::string(e.what()), f->message(f->name));
      }
    }
    EXPECT_EQ(codec_error(f->name, f->max), "accepted") << f->name;
  }
  for (const fields::IntegerField* f : fields::kIntegerFields) {
    EXPECT_EQ(solve[f->name]["minimum"].get<long long>(), f->min) << f->name;
    EXPECT_EQ(codec_error(f->name, f->min - 1), f->message(f->name)) << f->name;
    EXPECT_EQ(codec_error(f->name, f->max + 1), f->message(f->name)) << f->name;
  }
  EXPECT_EQ(fields::h.message("h"), "h must be a finite number in (0, 1e6]");
  EXPECT_EQ(fields::tol.range_text(), "[1e-16, 1]");
}

// The request contract is written once: a request schema lists exactly the rows of the field table its route
// takes, a render schema its picture options.
TEST(OpenApi, RequestSchemasAreTheFieldTable) {
  const json doc = json::parse(openapi_document(ServerOptions{}));
  const json& schemas = doc["components"]["schemas"];
  const std::pair<const char*, fields::Route> requests[] = {
      {"SolveRequest", fields::solve}, {"SweepRequest", fields::sweep}, {"BasinRequest", fields::basins},
      {"IntegrateRequest", fields::integrate}, {"WorkPrecisionRequest", fields::work_precision}};
  for (const auto& [name, route] : requests) {
    std::set<std::string> listed, rows;
    for (const auto& [key, _] : schemas[name]["properties"].items()) listed.insert(key);
    for (const fields::Field* row : fields::fields_of(route)) rows.insert(row->name);
    EXPECT_EQ(listed, rows) << name;
    EXPECT_EQ(schemas[name]["properties"]["group"]["default"], "SO") << name;
  }
  const std::pair<const char*, fields::Route> renders[] = {
      {"RenderFramesRequest", fields::render_frames}, {"RenderHeatmapRequest", fields::render_heatmap},
      {"RenderBasinsRequest", fields::render_basins}, {"RenderWorkPrecisionRequest", fields::render_work_precision},
      {"RenderResidualsRequest", fields::render_residuals}, {"RenderInvariantsRequest", fields::render_invariants},
      {"RenderMotionRequest", fields::render_motion}};
  for (const auto& [name, route] : renders) {
    std::set<std::string> listed, rows;
    for (const auto& [key, _] : schemas[name]["properties"].items()) listed.insert(key);
    for (const fields::Field& row : picture_fields())
      if (row.takes(route)) rows.insert(row.name);
    EXPECT_EQ(listed, rows) << name;
  }
}

// A default the document states is what the codec leaves in the request when the field is absent.
TEST(OpenApi, DefaultsAreWhatTheServerApplies) {
  const json doc = json::parse(openapi_document(ServerOptions{}));
  const json& schemas = doc["components"]["schemas"];
  const auto stated = [&](const char* schema, const char* field) { return schemas[schema]["properties"][field]["default"]; };
  const json none = json::object();
  const Limits limits;
  const SolveRequest solve = solve_request_from_json(none, limits);
  EXPECT_EQ(stated("SolveRequest", "h"), solve.h);
  EXPECT_EQ(stated("SolveRequest", "problem"), to_string(solve.problem.kind));
  EXPECT_EQ(stated("SolveRequest", "method"), to_string(solve.solver.method));
  EXPECT_EQ(stated("SolveRequest", "differential"), to_string(solve.solver.differential));
  const SweepRequest sweep = sweep_request_from_json(none, limits);
  EXPECT_EQ(stated("SweepRequest", "problem"), to_string(sweep.problem.kind));
  EXPECT_EQ(stated("SweepRequest", "differential"), to_string(sweep.solver.differential));
  const BasinRequest basins = basin_request_from_json(none, limits);
  EXPECT_EQ(stated("BasinRequest", "h"), basins.solve.h);
  EXPECT_EQ(stated("BasinRequest", "problem"), to_string(basins.solve.problem.kind));
  EXPECT_EQ(stated("BasinRequest", "differential"), to_string(basins.solve.solver.differential));
  const IntegrateRequest integrate = integrate_request_from_json(none, limits);
  EXPECT_EQ(stated("IntegrateRequest", "problem"), to_string(integrate.problem.kind));
  EXPECT_EQ(stated("IntegrateRequest", "method"), to_string(integrate.solver.method));
  EXPECT_EQ(stated("IntegrateRequest", "integrator"), to_string(integrate.integrator));
  EXPECT_FALSE(schemas["IntegrateRequest"]["properties"]["h"].contains("default"));  // from the field's time scale
  const WorkPrecisionRequest wp = work_precision_request_from_json(none, limits);
  EXPECT_EQ(stated("WorkPrecisionRequest", "problem"), to_string(wp.problem.kind));
  EXPECT_EQ(stated("WorkPrecisionChoice", "integrator"), to_string(WorkPrecisionChoice{}.integrator));
  // Every stream's records are told apart by type, each named in the mapping.
  for (const char* stream : {"SolveStreamRecord", "SweepStreamRecord", "BasinStreamRecord", "IntegrateStreamRecord",
                             "WorkPrecisionStreamRecord"}) {
    const json& s = schemas[stream];
    EXPECT_EQ(s["discriminator"]["propertyName"], "type") << stream;
    EXPECT_EQ(s["oneOf"].size(), s["discriminator"]["mapping"].size()) << stream;
    EXPECT_TRUE(s["discriminator"]["mapping"].contains("error")) << stream;
  }
}

// Descriptions are built from the code's constants, never typed again.
TEST(OpenApi, DescriptionsReadTheConstants) {
  const json doc = json::parse(openapi_document(ServerOptions{}));
  const json& solve = doc["components"]["schemas"]["SolveRequest"]["properties"];
  const auto has = [](const json& text, const std::string& part) {
    return text.get<std::string>().find(part) != std::string::npos;
  };
  EXPECT_TRUE(has(solve["watchdog"]["description"], "up to " + std::to_string(kWatchdogSteps) + " full steps"));
  EXPECT_TRUE(has(solve["watchdog"]["description"], "at most " + std::to_string(kWatchdogEpisodes) + " such"));
  const std::string threshold = "N = " + std::to_string(kKrylovThreshold) + ",";
  EXPECT_TRUE(has(solve["linear_solver"]["description"], threshold));
  for (const auto& entry : doc["x-lienewton"]["enums"]["linear_solver"]) {
    if (entry["value"] == "auto") {
      EXPECT_TRUE(has(entry["description"], threshold));
    }
  }
}

std::string css(render::Color c) {
  return "rgb(" + std::to_string(c.r) + "," + std::to_string(c.g) + "," + std::to_string(c.b) + ")";
}

// The dashboard asks for a motion only where the catalog says the group has bodies: every registered group is
// listed, SO(N) at N = 3 only (the rotations of space), the rigid-body groups at any n, a group without bodies (a
// test's matrix group) at none; each as draws_bodies, which the route asks, says.
TEST(OpenApi, GroupsSayWhereTheyDrawBodies) {
  const json doc = json::parse(openapi_document(ServerOptions{}));
  std::set<std::string> listed;
  for (const json& group : doc["x-lienewton"]["groups"]) {
    const std::string name = group["value"];
    listed.insert(name);
    if (name == "SO") {
      EXPECT_EQ(group["bodies_n"], json::array({3}));
    } else if (name == "SE" || name == "SOxR" || name == "SExR" || name == "SExR^k") {
      EXPECT_EQ(group["bodies_n"], "any") << name;
    }
    const GroupFamily& family = group_family(name);
    for (int n = 2; n <= service::kBodiesIndicesTried; ++n) {
      if (family.only_index() && n != *family.only_index()) continue;
      const bool listed_n = group["bodies_n"] == "any" || std::ranges::count(group["bodies_n"], json(n)) == 1;
      EXPECT_EQ(service::draws_bodies(family, n), listed_n) << name << " n = " << n;
    }
  }
  const std::vector<std::string> names = registered_group_names();
  EXPECT_EQ(listed, std::set<std::string>(names.begin(), names.end()));
}

// The dashboard reads its words and colours from "x-lienewton": every value the API accepts or answers has a
// label, a short label and a description, every status a colour, and the colours are the renderer's.
TEST(OpenApi, ExtensionLabelsEveryEnumValue) {
  const json doc = json::parse(openapi_document(ServerOptions{}));
  const json& schemas = doc["components"]["schemas"];
  const json& ext = doc["x-lienewton"];
  const std::pair<const char*, json> published[] = {
      {"problem", schemas["SolveRequest"]["properties"]["problem"]["enum"]},
      {"method", schemas["SolveRequest"]["properties"]["method"]["enum"]},
      {"differential", schemas["SolveRequest"]["properties"]["differential"]["enum"]},
      {"linear_solver", schemas["SolveRequest"]["properties"]["linear_solver"]["enum"]},
      {"integrator", schemas["IntegrateRequest"]["properties"]["integrator"]["enum"]},
      {"status", schemas["SolveResult"]["properties"]["status"]["enum"]},
      {"factorization", schemas["SolveResult"]["properties"]["linear_solver"]["enum"]},
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
  for (const auto& entry : ext["enums"]["integrator"]) {
    EXPECT_EQ(entry["solves_stages"], entry["value"] != "rkmk4") << entry["value"];
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
