#include "server/routes.hpp"

#include <string>

#include "core/options.hpp"
#include "core/vocabulary.hpp"
#include "server/api_handlers.hpp"

namespace lienewton::service {
namespace {

const std::vector<int> kJsonPostErrors{400, 403, 406, 411, 413, 415, 422, 429, 431, 503, 504};
const std::vector<int> kGetWorkErrors{400, 403, 413, 422, 429, 431, 503, 504};

// "energy, vertical momentum, ...": every invariant a built-in problem reports, from the vocabulary.
std::string invariant_names() {
  std::string names;
  for (Invariant i : kAllInvariants) names += (names.empty() ? "" : ", ") + std::string(words(i).short_label);
  return names;
}

std::vector<RouteSpec> build_table() {
  const std::string ndjson = "application/x-ndjson";
  std::vector<RouteSpec> t{
      {&ApiHandlers::solve_events, "GET", "/api/v1/solve/events",
       "The solve stream as Server-Sent Events (query parameters mirror SolveRequest)", BodyKind::none, true,
       "SolveRequest", {"text/event-stream"}, "SolveStreamRecord", kGetWorkErrors},
      {&ApiHandlers::render_frames, "POST", "/api/v1/render/frames",
       "PNG of the rotation frames (each state's rotation part: SO(3), or R of SE, SOxR, SExR) of a solve (iterates) or integration (trajectory)", BodyKind::json, true,
       "RenderFramesRequest", {"image/png", "image/svg+xml"}, "", kJsonPostErrors},
      {&ApiHandlers::render_frames, "GET", "/api/v1/render/frames",
       "GET form of render/frames for <img src> (query parameters mirror RenderFramesRequest)", BodyKind::none, true,
       "RenderFramesRequest", {"image/png", "image/svg+xml"}, "", kGetWorkErrors},
      {&ApiHandlers::render_motion, "POST", "/api/v1/render/motion",
       "The motion of a solve's iterates or an integration's states as a scene of bodies (solids from their inertia, "
       "a traced path coloured by time): an animated WebP, or one state as PNG/SVG", BodyKind::json, true,
       "RenderMotionRequest", {"image/webp", "image/png", "image/svg+xml"}, "", kJsonPostErrors},
      {&ApiHandlers::render_motion, "GET", "/api/v1/render/motion",
       "GET form of render/motion for <img src> (query parameters mirror RenderMotionRequest)", BodyKind::none, true,
       "RenderMotionRequest", {"image/webp", "image/png", "image/svg+xml"}, "", kGetWorkErrors},
      {&ApiHandlers::render_heatmap, "POST", "/api/v1/render/heatmap",
       "PNG heatmap of a sweep (a sweep request, or {\"sweep\": <sweep result>}, or both: the result titled by its request)", BodyKind::json, true,
       "RenderHeatmapRequest", {"image/png", "image/svg+xml"}, "", kJsonPostErrors},
      {&ApiHandlers::render_heatmap, "GET", "/api/v1/render/heatmap",
       "GET form of render/heatmap for <img src> (query parameters mirror the sweep request)", BodyKind::none, true,
       "RenderHeatmapRequest", {"image/png", "image/svg+xml"}, "", kGetWorkErrors},
      {&ApiHandlers::render_basins, "POST", "/api/v1/render/basins",
       "PNG basin map: one panel per method, roots in distinct hues shaded by iterations, failures in their colours",
       BodyKind::json, true, "RenderBasinsRequest", {"image/png", "image/svg+xml"}, "", kJsonPostErrors},
      {&ApiHandlers::render_basins, "GET", "/api/v1/render/basins",
       "GET form of render/basins for <img src> (query parameters mirror BasinRequest)", BodyKind::none, true,
       "RenderBasinsRequest", {"image/png", "image/svg+xml"}, "", kGetWorkErrors},
      {&ApiHandlers::render_work_precision, "POST", "/api/v1/render/work-precision",
       "PNG work-precision diagram: solver CPU time vs global error, one line per choice through its h, fitted order "
       "in the legend", BodyKind::json, true, "RenderWorkPrecisionRequest", {"image/png", "image/svg+xml"}, "", kJsonPostErrors},
      {&ApiHandlers::render_work_precision, "GET", "/api/v1/render/work-precision",
       "GET form of render/work-precision for <img src> (choices as JSON text)", BodyKind::none, true,
       "RenderWorkPrecisionRequest", {"image/png", "image/svg+xml"}, "", kGetWorkErrors},
      {&ApiHandlers::render_invariants, "POST", "/api/v1/render/invariants",
       "PNG of the drift of a problem's invariants (" + invariant_names() + ") over one integration's time",
       BodyKind::json, true, "RenderInvariantsRequest", {"image/png", "image/svg+xml"}, "", kJsonPostErrors},
      {&ApiHandlers::render_invariants, "GET", "/api/v1/render/invariants",
       "GET form of render/invariants for <img src> (query parameters mirror RenderInvariantsRequest)", BodyKind::none,
       true, "RenderInvariantsRequest", {"image/png", "image/svg+xml"}, "", kGetWorkErrors},
      {&ApiHandlers::render_residuals, "POST", "/api/v1/render/residuals",
       "PNG of ||f(y_n)|| vs solver CPU time beside ||f(y_n)|| vs iteration for every method x differential of one "
       "equation", BodyKind::json, true, "RenderResidualsRequest", {"image/png", "image/svg+xml"}, "", kJsonPostErrors},
      {&ApiHandlers::render_residuals, "GET", "/api/v1/render/residuals",
       "GET form of render/residuals for <img src> (query parameters mirror RenderResidualsRequest)", BodyKind::none,
       true, "RenderResidualsRequest", {"image/png", "image/svg+xml"}, "", kGetWorkErrors},
      {&ApiHandlers::livez, "GET", "/livez", "Liveness: answers while the process serves requests", BodyKind::none, false,
       "", {"application/json"}, "Health", {}, true},
      {&ApiHandlers::readyz, "GET", "/readyz", "Readiness: 503 while draining for shutdown", BodyKind::none, false, "",
       {"application/json"}, "Health", {503}, true},
      {&ApiHandlers::metrics, "GET", "/metrics", "Prometheus metrics (text exposition format 0.0.4)", BodyKind::none,
       false, "", {"text/plain"}, "", {}, true},
      {&ApiHandlers::openapi, "GET", "/openapi.json", "This document", BodyKind::none, false, "", {"application/json"}, "",
       {}},
      {&ApiHandlers::version, "GET", "/api/v1/version", "The release (as this document's info.version) and the build",
       BodyKind::none, false, "", {"application/json"}, "Version", {}, true},
      {&ApiHandlers::static_file, "GET", "/", "The dashboard (static files from the web root are served below /)",
       BodyKind::none, false, "", {"text/html"}, "", {404}},
  };
  // The compute commands' routes, one per row of the command table.
  for (const CommandSpec& c : command_table())
    t.push_back({&ApiHandlers::command, "POST", command_path(c.command), c.summary, BodyKind::json, true,
                 c.request_schema, {"application/json", ndjson}, c.result_schema, kJsonPostErrors});
  return t;
}

}  // namespace

const std::vector<RouteSpec>& route_table() {
  static const std::vector<RouteSpec> table = build_table();
  return table;
}

std::string command_path(Command command) { return "/api/v1/" + std::string(command_spec(command).name); }

const RouteSpec* find_route(const std::string& method, const std::string& path) {
  for (const auto& r : route_table()) {
    if (r.path == path && (r.method == method || (method == "HEAD" && r.method == "GET"))) return &r;
  }
  return nullptr;
}

bool path_is_routed(const std::string& path) {
  for (const auto& r : route_table()) {
    if (r.path == path) return true;
  }
  return false;
}

}  // namespace lienewton::service
