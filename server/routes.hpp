#pragma once
// The one route table: each row holds its handler; the server registers the handlers from it and the OpenAPI document is generated from
// it, so the two cannot disagree.
#include <string>
#include <vector>

#include "server/http_exchange.hpp"
#include "server/request_limits.hpp"
#include "server/request_runner.hpp"

namespace lienewton::service {

class ApiHandlers;
// A route's handler: a member of ApiHandlers from request value to response value.
using RouteHandler = HttpResponse (ApiHandlers::*)(const HttpRequest&);

struct RouteSpec {
  RouteHandler handler;
  std::string method;  // "GET" or "POST"
  std::string path;    // exact path
  std::string summary;
  BodyKind body;
  bool long_work;                          // takes a work slot; refused with 503 when none is free
  std::string request_schema;              // components/schemas name of the body or query, "" if none
  std::vector<std::string> success_types;  // media types of the 200 response
  std::string result_schema;               // schema of the application/json (or first) success type
  std::vector<int> errors;                 // documented error statuses
  bool serves_while_draining = false;      // health and metrics keep answering during a shutdown drain
};

// Every route this build serves (render routes only when the renderer is built in).
const std::vector<RouteSpec>& route_table();

// A compute command's route: POST /api/v1/<its name>.
std::string command_path(Command command);

// The route a path belongs to, ignoring the method; nullptr for static files and unknown paths.
const RouteSpec* find_route(const std::string& method, const std::string& path);
bool path_is_routed(const std::string& path);

struct ServerOptions;
// The OpenAPI 3.0 document for route_table(), with the running server's limits in x-lienewton.
std::string openapi_document(const ServerOptions& options);

}  // namespace lienewton::service
