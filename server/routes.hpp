#pragma once
// The one route table: the server registers its handlers from it and the OpenAPI document is generated from
// it, so the two cannot disagree.
#include <string>
#include <vector>

#include "server/request_limits.hpp"

namespace lienewton::service {

enum class RouteId {
  solve,
  solve_events,
  sweep,
  integrate,
  work_precision,
  render_frames_post,
  render_frames_get,
  render_heatmap_post,
  render_heatmap_get,
  livez,
  readyz,
  metrics,
  openapi,
  index,
};

struct RouteSpec {
  RouteId id;
  std::string method;  // "GET" or "POST"
  std::string path;    // exact path
  std::string summary;
  BodyKind body;
  bool long_work;                          // takes a work slot; refused with 503 when none is free
  std::string request_schema;              // components/schemas name of the body or query, "" if none
  std::vector<std::string> success_types;  // media types of the 200 response
  std::string result_schema;               // schema of the application/json (or first) success type
  std::vector<int> errors;                 // documented error statuses
};

// Every route this build serves (render routes only when the renderer is built in).
const std::vector<RouteSpec>& route_table();

// The route a path belongs to, ignoring the method; nullptr for static files and unknown paths.
const RouteSpec* find_route(const std::string& method, const std::string& path);
bool path_is_routed(const std::string& path);

// The OpenAPI 3.0 document for route_table().
std::string openapi_document();

}  // namespace lienewton::service
