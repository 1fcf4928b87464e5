// The OpenAPI 3.0 document, generated from the route table plus the schemas of the JSON contract.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>
#include <nlohmann/json.hpp>

#include "core/basins.hpp"
#include "core/options.hpp"
#include "core/status.hpp"
#include "core/vocabulary.hpp"
#include "core/fields.hpp"
#include "core/group_registry.hpp"
#include "core/solvers/iteration_monitor.hpp"
#include "server/json_codec.hpp"
#include "server/openapi_examples.hpp"
#include "server/openapi_labels.hpp"
#include "server/render_requests.hpp"
#include "server/routes.hpp"

namespace lienewton::service {
namespace {

using nlohmann::json;

template <class Enum, std::size_t K>
json enum_schema(const Enum (&all)[K], const char* description) {
  json values = json::array();
  for (auto e : all) values.push_back(std::string(to_string(e)));
  return json{{"type", "string"}, {"enum", values}, {"description", description}};
}

template <class Enum, std::size_t K>
json nullable_enum(const Enum (&all)[K], const char* description) {
  json schema = enum_schema(all, description);
  schema["nullable"] = true;
  return schema;
}

// What a result's linear_solver says.
constexpr const char* kFactorizationUsed =
    "how the Newton systems were factored: dense-lu, sparse-lu (a system of bodies whose Newton matrix is large: "
    "its block sparsity kept) or gmres (matrix-free); an integration that used two reports the larger kind, and "
    "null when it solved no linear system (explicit methods, the fixed point)";

// The group's names, or the shorthand <body>^<k> of a family named <body>^k that bounds its index (json_codec.cpp
// reads "SExR^8" as {"group": "SExR^k", "n": 8}).
json with_power_shorthand(json s) {
  std::string bodies;
  for (const std::string& name : registered_group_names()) {
    if (name.size() < 2 || name.compare(name.size() - 2, 2, "^k") != 0 || !group_family(name).max_index()) continue;
    bodies += (bodies.empty() ? "" : "|") + name.substr(0, name.size() - 2);
  }
  if (bodies.empty()) return s;
  json names{{"type", "string"}, {"enum", s["enum"]}};
  s.erase("enum");
  s["anyOf"] = json::array({names, json{{"type", "string"}, {"pattern", "^(" + bodies + ")\\^[0-9]+$"}}});
  return s;
}

json ref(const std::string& name) { return json{{"$ref", "#/components/schemas/" + name}}; }
json number(const char* description) { return json{{"type", "number"}, {"description", description}}; }
json nullable_number(const char* description) {
  return json{{"type", "number"}, {"nullable", true}, {"description", description}};
}
// One nullable number per invariant (core/invariants.hpp), named prefix + its API name + suffix, described by
// what + the invariant's sentence.
json invariant_numbers(json properties, const std::string& prefix, const std::string& suffix, const std::string& what) {
  for (Invariant i : kAllInvariants)
    properties[prefix + std::string(to_string(i)) + suffix] =
        json{{"type", "number"}, {"nullable", true},
             {"description", what + std::string(words(i).sentence) + " (null where the problem has no such invariant)"}};
  return properties;
}
json integer(const char* description) { return json{{"type", "integer"}, {"description", description}}; }
json nullable_integer(const std::string& description) {
  return json{{"type", "integer"}, {"nullable", true}, {"description", description}};
}
constexpr const char* kJacobianEvaluations =
    "RKMK methods: Newton matrices formed (Jacobians dg or the stage system's); the simplified Newton "
    "(differential dexpinv-0) keeps its matrix across steps while it contracts; null for DIRK methods";
constexpr const char* kFactorizations = "RKMK methods: LU factorizations made; null for DIRK methods";
json array_of(json items) { return json{{"type", "array"}, {"items", std::move(items)}}; }
json object(json properties, std::vector<std::string> required = {}, bool closed = true) {
  json o{{"type", "object"}, {"properties", std::move(properties)}};
  if (!required.empty()) o["required"] = required;
  if (closed) o["additionalProperties"] = false;
  return o;
}
// Where a limit of the server's stands for a row's maximum in the schema (sweep threads): its default.
long long default_cap(fields::Cap cap) {
  const Limits limits;
  switch (cap) {
    case fields::Cap::n: return limits.max_n;
    case fields::Cap::iterations: return limits.max_iterations;
    case fields::Cap::threads: return limits.max_threads;
    case fields::Cap::frames: return limits.max_frames;
    case fields::Cap::grid_axis: return static_cast<long long>(limits.max_grid_cells);
    case fields::Cap::none: break;
  }
  return 0;
}

json properties(const std::vector<const fields::Field*>& rows);

// A request field's schema, from its row in the field table (core/fields.hpp, picture options in
// server/render_requests.cpp): type, bounds, enum and default on the value (an array's items), the
// description on the field.
json schema_of(const fields::Field& f) {
  using fields::Type;
  const auto bound = [&](double x) {  // an integer field's bounds are integers, where one holds them
    return f.type == Type::integer && std::abs(x) < 9e18 ? json(static_cast<long long>(x)) : json(x);
  };
  json s;
  switch (f.type) {
    case Type::number: s = {{"type", "number"}}; break;
    case Type::integer: s = {{"type", "integer"}}; break;
    case Type::boolean: s = {{"type", "boolean"}}; break;
    case Type::string: s = {{"type", "string"}}; break;
    case Type::matrix: s = array_of(array_of(json{{"type", "number"}})); break;
    case Type::object: {
      std::vector<const fields::Field*> rows;
      for (const fields::Field& p : f.properties) rows.push_back(&p);
      if (!f.schema.empty()) s = ref(f.schema);
      else if (rows.empty())  // named values (parameters): a number, a row or a matrix each
        s = json{{"type", "object"},
                 {"additionalProperties", {{"anyOf", json::array({json{{"type", "number"}}, array_of(json{{"type", "number"}}),
                                                                  array_of(array_of(json{{"type", "number"}}))})}}}};
      else s = object(properties(rows), f.required);
      break;
    }
  }
  if (f.type == Type::number || f.type == Type::integer) {
    if (const auto min = f.schema_minimum ? f.schema_minimum : f.minimum) s["minimum"] = bound(*min);
    if (f.exclusive_minimum) s["exclusiveMinimum"] = true;
    std::optional<double> max = f.schema_maximum;
    if (!max && f.publish_cap) max = static_cast<double>(default_cap(f.cap));
    if (!max && f.cap == fields::Cap::none) max = f.maximum;
    if (max) s["maximum"] = bound(*max);
  }
  if (!f.values.empty()) s["enum"] = f.values;
  if (f.name == "group") s = with_power_shorthand(std::move(s));
  std::visit([&](const auto& d) {
    if constexpr (!std::is_same_v<std::decay_t<decltype(d)>, std::monostate>) s["default"] = d;
  }, f.default_value);
  if (f.array) {
    s = json{{"type", "array"}, {"items", std::move(s)}};
    if (f.max_items > 0 && f.min_items == f.max_items) {  // a fixed length (rigid_body's vectors) is part of the type
      s["minItems"] = f.min_items;
      s["maxItems"] = f.max_items;
    }
  }
  if (!f.description.empty() && !s.contains("$ref")) s["description"] = f.description;
  return s;
}

json properties(const std::vector<const fields::Field*>& rows) {
  json out = json::object();
  for (const fields::Field* row : rows) out[row->name] = schema_of(*row);
  return out;
}

// "960 x 640"
std::string size_text(FigureSize size) { return std::to_string(size.width) + " x " + std::to_string(size.height); }

// The picture options a render route takes.
std::vector<const fields::Field*> picture_rows(fields::Route route) {
  std::vector<const fields::Field*> out;
  for (const fields::Field& f : picture_fields())
    if (f.takes(route)) out.push_back(&f);
  return out;
}

// The named schemas of object rows (RigidBody, WorkPrecisionChoice), from their properties.
void add_object_schemas(json& s, const std::vector<fields::Field>& rows) {
  for (const fields::Field& f : rows) {
    if (f.schema.empty() || f.properties.empty()) continue;
    std::vector<const fields::Field*> props;
    for (const fields::Field& p : f.properties) props.push_back(&p);
    s[f.schema] = object(properties(props));
  }
}


json matrix(const char* description) {
  json m = array_of(array_of(json{{"type", "number"}}));
  m["description"] = description;
  return m;
}

// Every code an error carries (the service's and the CLI's): the codec's (json_codec.cpp), the front end's
// refusals (request_limits.cpp, http_server.cpp), the handlers' (ApiError) and the CLI's own (usage,
// input_failed, output_failed). tests/replay/validate_answers.py checks the sources name no other.
json error_codes() {
  static const char* const kCodes[] = {
      "invalid_field", "unknown_field", "duplicate_field", "malformed_json", "unprocessable", "program_too_large",
      "output_too_large", "bad_request", "not_found", "method_not_allowed", "length_required", "invalid_content_length",
      "unexpected_body", "body_too_large", "incomplete_body", "uri_too_long", "unsupported_media_type",
      "unsupported_content_encoding", "not_acceptable", "cross_site", "multiple_ranges", "range_not_satisfiable",
      "invalid_header", "too_many_headers", "client_over_capacity", "over_capacity", "server_busy", "shutting_down",
      "deadline_exceeded", "client_gone", "render_unavailable", "out_of_memory", "internal_error", "error", "usage",
      "input_failed", "output_failed"};
  json values = json::array();
  for (const char* code : kCodes) values.push_back(code);
  return json{{"type", "string"}, {"enum", values},
              {"description", "what went wrong, for a program to branch on (the status says how bad; message says it "
                              "to a person). error: a status the server has no own code for; usage, "
                              "input_failed and output_failed: the CLI only"}};
}

// A stream's record of kind `type`: the named schema `of` plus its type.
json stream_record(const json& s, const std::string& of, const std::string& type, const std::string& description) {
  json r = s.at(of);
  r["properties"]["type"] = json{{"type", "string"}, {"enum", {type}}};
  json required = r.value("required", json::array());
  required.push_back("type");
  r["required"] = required;
  r["description"] = description;
  return r;
}

// The NDJSON lines (and SSE data fields) of each streaming route: progress records, then exactly one terminal
// record, result (the fields of the non-streamed result) or error. Each route's stream is a oneOf told apart by
// type (the discriminator).
void add_stream_records(json& s) {
  s["IterationRecord"] = stream_record(s, "TraceRecord", "iteration", "a solve's iteration (TraceRecord)");
  s["PathPointRecord"] = stream_record(s, "TraceRecord", "path_point",
                                       "continuation: a point of the path (TraceRecord with path_point)");
  s["PathPointRecord"]["required"].push_back("path_point");
  s["CellRecord"] = stream_record(s, "SweepCell", "cell", "a finished sweep cell");
  s["StepStreamRecord"] = stream_record(s, "StepRecord", "step", "an integration step");
  s["SeriesRecord"] = stream_record(s, "WorkPrecisionSeries", "series", "a finished work-precision series");
  s["GridRecord"] = stream_record(s, "BasinGrid", "grid", "the basin map's grid, first");
  s["RowRecord"] = stream_record(s, "BasinRow", "row", "a finished row of the basin map");
  s["SolveResultRecord"] = stream_record(s, "SolveResult", "result", "the solve's result, last");
  s["SweepResultRecord"] = stream_record(s, "SweepResult", "result", "the sweep's result, last");
  json summary = stream_record(s, "BasinResult", "result", "the basin map's summary, last: BasinResult without grid and rows");
  summary["properties"].erase("grid");
  summary["properties"].erase("rows");
  json required = json::array();
  for (const auto& name : summary["required"])
    if (name != "grid" && name != "rows") required.push_back(name);
  summary["required"] = required;
  s["BasinSummaryRecord"] = summary;
  s["IntegrateResultRecord"] = stream_record(s, "IntegrateResult", "result", "the integration's result, last");
  s["WorkPrecisionResultRecord"] = stream_record(s, "WorkPrecisionResult", "result", "the work-precision result, last");
  s["ErrorRecord"] = stream_record(s, "Error", "error", "the work failed after the stream began: the error, last");
  const auto stream = [&](const char* name, const char* what,
                          std::vector<std::pair<std::string, std::string>> records) {
    json one_of = json::array(), mapping = json::object();
    records.emplace_back("error", "ErrorRecord");
    for (const auto& [type, schema] : records) {
      one_of.push_back(ref(schema));
      mapping[type] = "#/components/schemas/" + schema;
    }
    s[name] = json{{"description", what}, {"oneOf", one_of},
                   {"discriminator", {{"propertyName", "type"}, {"mapping", mapping}}}};
  };
  stream("SolveStreamRecord", "One NDJSON line (or SSE data field) of a solve: iteration and path_point records, then result or error.",
         {{"iteration", "IterationRecord"}, {"path_point", "PathPointRecord"}, {"result", "SolveResultRecord"}});
  stream("SweepStreamRecord", "One NDJSON line of a sweep: a cell record per finished cell, then result or error.",
         {{"cell", "CellRecord"}, {"result", "SweepResultRecord"}});
  stream("BasinStreamRecord", "One NDJSON line of a basin map: grid, a row record per finished row, then the summary or error.",
         {{"grid", "GridRecord"}, {"row", "RowRecord"}, {"result", "BasinSummaryRecord"}});
  stream("IntegrateStreamRecord", "One NDJSON line of an integration: a step record per step, then result or error.",
         {{"step", "StepStreamRecord"}, {"result", "IntegrateResultRecord"}});
  stream("WorkPrecisionStreamRecord", "One NDJSON line of work-precision: a series record per choice, then result or error.",
         {{"series", "SeriesRecord"}, {"result", "WorkPrecisionResultRecord"}});
}

json schemas() {
  const json method = schema_of(*fields::find(fields::solve, "method"));
  const json globalization = schema_of(*fields::find(fields::solve, "globalization"));
  const json status = enum_schema(kAllStatuses, "how the solve ended");
  json s;
  // The requests: a route's schema is the rows whose route set includes it.
  const std::pair<const char*, fields::Route> requests[] = {
      {"SolveRequest", fields::solve}, {"SweepRequest", fields::sweep}, {"BasinRequest", fields::basins},
      {"IntegrateRequest", fields::integrate}, {"WorkPrecisionRequest", fields::work_precision}};
  for (const auto& [name, route] : requests) s[name] = object(properties(fields::fields_of(route)));
  add_object_schemas(s, fields::request_fields());
  add_object_schemas(s, picture_fields());
  const json trace_props = {{"iteration", integer("n")},
                            {"residual", nullable_number("||f(y_n)||, f(y) = log(z^-1 y) - h g(y) (3.6), every method")},
                            {"algebra_residual", nullable_number("||f~(v_n)|| (3.21): Version 2 and the fixed point only")},
                            {"step", nullable_number("||u_{n-1}||")}, {"angle", nullable_number("largest rotation angle of z^-1 y_n")},
                            {"distance_to_pi", nullable_number("pi - angle")},
                            {"orthogonality_error", nullable_number("||y^T y - I||_F")},
                            {"seconds", nullable_number("wall time since the solve started")},
                            {"cpu_seconds", nullable_number("solver CPU time so far: the solving thread's CPU time, less what "
                                                            "streaming the records cost (as work-precision times its runs)")},
                            {"step_kind", json{{"type", "string"}, {"enum", {"newton", "levenberg-marquardt", "dogleg", "cauchy", "watchdog"}},
                                               {"description", "globalised Newton only: how u_{n-1} was found (watchdog: "
                                                               "a full Newton step that did not decrease 1/2 ||f||^2, or, "
                                                               "with step 0 and step_from_iterate, the return to that "
                                                               "iterate where the strategy finds no step from it)"}}},
                            {"step_length", nullable_number("line search only: the accepted alpha of y_{n-1} exp(alpha u)")},
                            {"trust_radius", nullable_number("trust region only: the radius u_{n-1} was taken in")},
                            {"step_from_iterate", json{{"type", "integer"},
                                                       {"description", "globalised Newton only: the watchdog went back "
                                                                       "to this earlier iterate and u_{n-1} starts there"}}},
                            {"stage_h", nullable_number("continuation only: the h of the equation this record belongs to "
                                                        "(streams carry the path's points and every solve's records, the result's trace the last solve's)")},
                            {"path_point", ref("PathPoint")},
                            {"y", matrix("iterate, only with include_iterates")}};
  s["PathPoint"] = object({{"kind", enum_schema(kAllPathPointKinds, "path: a corrected root (v, h) of v - h g(z exp v) = 0 on z's branch; final: the method's solve at the requested h; fold: where the branch turns back in h")},
                           {"h", number("the point's step size")}, {"status", status},
                           {"iterations", integer("the corrector's Newton iterations (final: the method's)")},
                           {"residual", nullable_number("||v - h g(z exp v)|| (final: ||f(y)|| of the method's y)")},
                           {"distance", nullable_number("||v||, v = log(z^-1 y) continued along the branch")},
                           {"angle", nullable_number("largest rotation angle of v")},
                           {"dh_ds", nullable_number("h-component of the branch's unit tangent; its sign change is a fold")},
                           {"step_length", nullable_number("arclength of the predictor step that reached the point")}},
                          {"kind", "h", "status", "iterations", "residual"}, false);
  s["TraceRecord"] = object(trace_props, {"iteration", "residual", "step", "angle", "distance_to_pi", "orthogonality_error", "seconds", "cpu_seconds"}, false);
  s["SolveResult"] = object({{"status", status}, {"reason", json{{"type", "string"}}}, {"iterations", integer("iterations done")},
                             {"rate", nullable_number("convergence rate r (null when fewer than 3 iterations)")},
                             {"rate_reliable", json{{"type", "boolean"}, {"description", "the last three residuals decrease and r is in [0.5, 3]"}}},
                             {"iterate", integer("n of the returned y = y_n (the best iterate when stagnated)")},
                             {"residual", nullable_number("||f(y)|| of the returned y")},
                             {"algebra_residual", nullable_number("||f~(v)|| of the returned y (Version 2, fixed point)")},
                             {"floor", nullable_number("rounding floor 64 eps sqrt(q) (1 + ||f|| + ||v|| + h||g|| + h||dg||)")},
                             {"orthogonality_error", nullable_number("||y^T y - I||_F of the returned y")},
                             {"z_adjustment", nullable_number("||z - polar(z)||_F: how far the z rule moved the given z")},
                             {"reorthogonalisations", integer("iterates replaced by their polar factor (drift)")},
                             {"y", matrix("the returned iterate y_iterate")}, {"trace", array_of(ref("TraceRecord"))},
                             {"seconds", number("wall time")},
                             {"cpu_seconds", number("solver CPU time of the whole solve (see TraceRecord.cpu_seconds)")},
                             {"linear_solver", enum_schema(kAllFactorizations, kFactorizationUsed)},
                             {"branch", enum_schema(kAllBranches, "which root y is: continued = reached by following z's branch of roots from h = 0 to h, no fold passed; other = known not to be that root; unchecked = not checked (a plain solve)")},
                             {"found_by", enum_schema(kAllSearches, "which search produced y: the plain solve, continuation, or a multistart start")},
                             {"distance_from_z", number("||y - z||_F")},
                             {"total_iterations", integer("iterations of the whole search: the returned solve's, the path's correctors' and every other solve's")},
                             {"fold_h", nullable_number("continuation only: the h at which z's branch turns back (status fold when below the requested h)")},
                             {"path_h", nullable_number("continuation only: the h the path reached when it stopped short of h")},
                             {"multistart_start", integer("found_by multistart: the seed k of the start y0 exp(x_k)")},
                             {"multistart_tries", integer("seeded starts solved")},
                             {"continuation", object({{"stages", array_of(ref("PathPoint"))},
                                                      {"total_iterations", integer("the same as the result's total_iterations")}},
                                                     {}, false)}},
                            {"status", "reason", "iterations", "rate", "rate_reliable", "iterate", "residual", "floor",
                             "orthogonality_error", "z_adjustment", "reorthogonalisations", "y", "trace", "seconds",
                             "cpu_seconds", "linear_solver"}, false);
  s["SweepCell"] = object({{"method", method}, {"n", integer("N")}, {"h", number("step size")}, {"status", status},
                           {"reason", json{{"type", "string"}}}, {"iterations", integer("")},
                           {"rate", nullable_number("")}, {"residual", nullable_number("")}},
                          {"method", "n", "h", "status", "reason", "iterations", "rate", "residual"}, false);
  s["SweepResult"] = object({{"cells", array_of(ref("SweepCell"))}, {"seconds", number("wall time")},
                             {"shard", object({{"index", integer("")}, {"count", integer("")},
                                               {"grid_cells", integer("cells of the whole grid")},
                                               {"cell_indices", array_of(integer("grid position of each cell"))}},
                                              {"index", "count", "grid_cells", "cell_indices"})}},
                            {"cells", "seconds"}, false);
  const json pixel_lists = object({{"method", method}, {"status", array_of(status)},
                                   {"root", array_of(json{{"type", "integer"}, {"nullable", true}})},
                                   {"iterations", array_of(json{{"type", "integer"}})}}, {}, false);
  s["BasinRoot"] = object({{"id", integer("root number, in pixel order of first arrival")},
                           {"y", matrix("the root (the first converged y of its cluster)")},
                           {"residual", nullable_number("||f(y)||")},
                           {"distance_from_z", nullable_number("||log(z^-1 y)||")},
                           {"hg_angle", nullable_number("largest rotation angle of h g(y)")}}, {}, false);
  s["BasinGrid"] = object({{"a", array_of(number("pixel-centre a of each column"))},
                           {"b", array_of(number("pixel-centre b of each row"))}, {"r", number("r")},
                           {"b1", array_of(number(""))}, {"b2", array_of(number(""))},
                           {"z", matrix("the equation's z (its orthogonal polar factor)")}}, {}, false);
  s["BasinRow"] = object({{"row", integer("row index (b ascending)")}, {"b", number("")},
                          {"methods", array_of(pixel_lists)},
                          {"new_roots", array_of(ref("BasinRoot"))}}, {}, false);
  s["BasinResult"] = object(
      {{"grid", ref("BasinGrid")}, {"rows", array_of(ref("BasinRow"))}, {"roots", array_of(ref("BasinRoot"))},
       {"methods", array_of(object({{"method", method}, {"pixels", integer("")}, {"converged", integer("")},
                                    {"converged_fraction", number("")}, {"basins", integer("distinct roots reached")},
                                    {"mean_iterations", nullable_number("over converged pixels")},
                                    {"statuses", json{{"type", "object"}, {"additionalProperties", {{"type", "integer"}}}}}},
                                   {}, false))},
       {"complete", json{{"type", "boolean"}}}, {"seconds", number("wall time")},
       {"shard", object({{"index", integer("")}, {"count", integer("")},
                         {"rows", array_of(integer("a row of the map this part holds"))},
                         {"request", json{{"type", "object"}, {"description", "the request without shard: "
                                                                               "lienewton merge refuses parts of "
                                                                               "different requests"}}}},
                        {"index", "count", "rows"})}},
      {"grid", "rows", "roots", "methods", "complete", "seconds"}, false);
  s["StepRecord"] = object({{"step", integer("1-based")}, {"t", number("")}, {"iterations", integer("summed over stages")},
                            {"residual", nullable_number("")}, {"status", status},
                            {"substeps", integer("steps taken inside this output step: more than 1 where halving kept the solution's branch "
                                                 "(adaptive: 2, the half steps whose product is y)")},
                            {"h", number("the step's size (adaptive: the accepted step)")},
                            {"error_estimate", nullable_number("adaptive: the accepted step's scaled local error estimate "
                                                               "(implicit RKMK: embedded; others: step doubling; at most "
                                                               "1); null with fixed steps")},
                            {"rejected", integer("adaptive: tries rejected before this step was accepted")},
                            {"jacobian_evaluations", nullable_integer(kJacobianEvaluations)},
                            {"factorizations", nullable_integer(kFactorizations)}},
                           {}, false);
  s["StepRecord"]["properties"] = invariant_numbers(s["StepRecord"]["properties"], "", "", "at the step's end state: ");
  s["IntegrateResult"] = object({{"status", status}, {"reason", json{{"type", "string"}}}, {"steps", array_of(ref("StepRecord"))},
                                 {"global_error", nullable_number("||y_N - y_ref(t_end)||_F")},
                                 {"reference_error", nullable_number("y_ref(t_end)'s estimated error: the distance of its last two "
                                                                     "refinements over 2^p - 1, p the reference method's order")},
                                 {"global_error_at_reference",
                                  json{{"type", "boolean"},
                                       {"description", "global_error is within 10x of reference_error: it bounds the run's "
                                                       "error rather than measuring it"}}},
                                 {"orthogonality_error", nullable_number("")},
                                 {"total_iterations", integer("iterations summed over every stage of every step")},
                                 {"substeps", integer("steps taken, halved ones counted as theirs")},
                                 {"mean_iterations", nullable_number("total_iterations per step")},
                                 {"jacobian_evaluations", nullable_integer(std::string(kJacobianEvaluations) + ", summed over the steps")},
                                 {"factorizations", nullable_integer(std::string(kFactorizations) + ", summed over the steps")},
                                 {"linear_solver", nullable_enum(kAllFactorizations, kFactorizationUsed)},
                                 {"y", matrix("final state")},
                                 {"frames", array_of(matrix("state"))}, {"frame_times", array_of(json{{"type", "number"}})},
                                 {"frame_steps", json{{"type", "array"}, {"items", integer("")},
                                                      {"description", "the step k of each frame (0: y(0)); the frames "
                                                                      "of render/frames with the same request"}}},
                                 {"cpu_seconds", number("")}, {"reference_seconds", number("")},
                                 {"adaptive", json{{"type", "boolean"}, {"description", "the steps were chosen by the error estimate (rtol/atol)"}}},
                                 {"rejected", integer("adaptive: tries rejected, summed over the steps")},
                                 {"h", number("the request's step, or its default from the problem's time scale "
                                              "(adaptive: the first step tried)")},
                                 {"warnings",
                                  json{{"type", "array"},
                                       {"items", object({{"code", json{{"type", "string"},
                                                                       {"enum", {kStepEnlarged, kInaccurate,
                                                                                 kInvariantDrift}}}},
                                                         {"message", json{{"type", "string"}}}},
                                                        {"code", "message"})},
                                       {"description",
                                        "what a converged run's answer warns of: " + std::string(kStepEnlarged) +
                                            " (a default step more than " + format_number(kDefaultStepOverTimeScale) +
                                            "x the field's time scale 1/rho, raised to fit the step budget), " +
                                            kInaccurate + " (global_error above " +
                                            format_number(kInaccurateFraction) + " of ||y_ref(t_end)||_F), " +
                                            kInvariantDrift + " (an invariant of the exact flow drifting by more "
                                            "than " + format_number(kInvariantDriftWarning) + " of its scale)"}}}},
                                {}, false);
  s["IntegrateResult"]["properties"] =
      invariant_numbers(invariant_numbers(invariant_numbers(s["IntegrateResult"]["properties"], "initial_", "", "at y(0): "),
                                          "", "_scale", "the size the drift is relative to (1 where it is 0), of "),
                        "", "_drift", "max over the steps of |I(y_k) - I(y(0))| / I_scale, I = ");
  json deprecated_error = nullable_number("deprecated: the old name of global_error, the same number");
  deprecated_error["deprecated"] = true;
  s["WorkPrecisionSeries"] = object({{"choice", ref("WorkPrecisionChoice")},
                                   {"points", array_of(object(invariant_numbers(json{{"h", number("")}, {"cpu_seconds", number("")},
                                                               {"global_error", nullable_number("||y_N - y_ref(t_end)||_F, as IntegrateResult's")},
                                                               {"error", deprecated_error},
                                                               {"status", status}, {"iterations", integer("")},
                                                               {"substeps", integer("steps taken (halving included)")},
                                                               {"tolerance", nullable_number("against tolerance: the run's rtol = atol (null with fixed steps; h is then the mean accepted step)")},
                                                               {"rejected", integer("adaptive: tries rejected")},
                                                               {"in_fit", json{{"type", "boolean"}, {"description", "the order is fitted from this point"}}},
                                                               {"excluded", json{{"type", "string"}, {"description", "why the fit leaves the point out"}}}}, "", "_drift",
                                                               "the run's drift (as IntegrateResult's) of "), {}, false))},
                                   {"fitted_order", nullable_number("observed order: least-squares slope of log error vs log h "
                                                                    "over the points in the asymptotic regime: converged on the solution's "
                                                                    "branch, the error 10x above the reference's estimated error and below 0.05 "
                                                                    "||y_ref||, consecutive slopes agreeing (null with fewer than three; "
                                                                    "fit_reason says why)")},
                                   {"fit_reason", json{{"type", "string"}, {"description", "how the order was fitted, or why it is null"}}},
                                   {"fit_h", array_of(number("an h the order is fitted from"))}},
                                  {}, false);
  s["WorkPrecisionResult"] = object({{"series", array_of(ref("WorkPrecisionSeries"))}, {"seconds", number("")},
                                     {"reference_error", nullable_number("the reference's estimated error (as IntegrateResult's); "
                                                                         "points within 10x of it are not fitted")},
                                     {"reference_seconds", number("")}}, {}, false);
  s["RenderFramesRequest"] = json{
      {"description", "A SolveRequest (n = 3; its iterates are drawn) or an IntegrateRequest (detected by kind = "
                      "\"integrate\" or by any of integrator/t_end/frames; the trajectory's states are drawn, frames "
                      "defaults to 16), plus the picture options below. Other N: 422."},
      {"type", "object"},
      {"properties", properties(picture_rows(fields::render_frames))}};
  s["RenderMotionRequest"] = json{
      {"description", "The requests of RenderFramesRequest (a SolveRequest, whose iterates are shown, at most " +
                      std::to_string(kMotionFrames + 1) + " of them evenly spaced; or an IntegrateRequest whose frames "
                      "default to " + std::to_string(kMotionFrames) + "), drawn as a scene of bodies: the heavy top as a disc on a rod "
                      "from its pivot with its symmetry axis' tip traced, the free rigid body's momentum on its sphere with "
                      "the energy levels, the stiff body's inertia ellipsoid, the chain's links; any other group's bodies "
                      "as ellipsoids. The animated WebP's XMP metadata names each frame's time (lienewton:frameTimes, "
                      "and lienewton:timeName: t, or n for iterates). Plus the picture options below."},
      {"type", "object"},
      {"properties", properties(picture_rows(fields::render_motion))}};
  s["RenderHeatmapRequest"] = json{
      {"description", "A SweepRequest, or {\"sweep\": SweepResult}, plus metric/width/height (0 or absent: automatic)."},
      {"type", "object"},
      {"properties", properties(picture_rows(fields::render_heatmap))}};
  // A sweep result to draw is read without its timing.
  json drawn_sweep = s["SweepResult"];
  drawn_sweep["required"] = json::array({"cells"});
  drawn_sweep["description"] = "a SweepResult to draw instead of running the sweep (seconds may be left out)";
  s["RenderHeatmapRequest"]["properties"]["sweep"] = drawn_sweep;
  s["RenderBasinsRequest"] = json{
      {"description", "A BasinRequest plus width/height (0 or absent: automatic)."},
      {"type", "object"},
      {"properties", properties(picture_rows(fields::render_basins))}};
  s["RenderWorkPrecisionRequest"] = json{
      {"description", "A WorkPrecisionRequest plus width/height (default " + size_text(kWorkPrecisionFigure) +
                          "). Each choice is one line through its converged h (largest first), styled as "
                          "x-lienewton.series_styles in order; the legend gives the fitted order p. No converged run "
                          "at all: 422."},
      {"type", "object"},
      {"properties", properties(picture_rows(fields::render_work_precision))}};
  s["RenderResidualsRequest"] = json{
      {"description", "A SolveRequest without method and differential, plus the lists below and width/height "
                      "(default " + size_text(kResidualsFigure) + "). One solve per method x differential (fixed point once); left panel "
                      "||f(y_n)|| against the solver's own CPU time (TraceRecord.cpu_seconds), right panel against n."},
      {"type", "object"},
      {"properties", properties(picture_rows(fields::render_residuals))}};
  s["RenderInvariantsRequest"] = json{
      {"description", "An IntegrateRequest of a problem with invariants (" + problems_with_invariants() +
                      "; else 422 naming problem) plus width/height (default " + size_text(kInvariantsFigure) + "). One line per "
                      "invariant: |I(y_k) - I(y_0)| / scale against the step k, log scale, the scale as IntegrateResult's "
                      "<invariant>_scale; a run that does not converge: 422."},
      {"type", "object"},
      {"properties", properties(picture_rows(fields::render_invariants))}};
  s["Health"] = object({{"status", json{{"type", "string"}, {"enum", {"ok", "draining", "saturated"}}}}}, {"status"}, false);
  s["ErrorDetail"] = object({{"code", error_codes()},
                             {"field", json{{"type", "string"}, {"nullable", true}, {"description", "the offending request field"}}},
                             {"message", json{{"type", "string"}}},
                             {"line", json{{"type", "integer"}, {"description", "a program's error (field g): its line, from 1"}}},
                             {"column", json{{"type", "integer"}, {"description", "a program's error: its column, from 1"}}}},
                            {"code", "field", "message"}, false);
  s["Error"] = object({{"error", ref("ErrorDetail")}}, {"error"}, false);
  s["Version"] = object({{"version", json{{"type", "string"}, {"description", "the release, as info.version"}}},
                         {"build", json{{"type", "string"}, {"description", "a hash of this server's binary"}}}},
                        {"version", "build"}, false);
  add_stream_records(s);
  return s;
}

std::string status_text(int status) {
  switch (status) {
    case 400: return "Malformed or invalid request (the error names the field)";
    case 403: return "Cross-site request (Sec-Fetch-Site cross-site, or Origin not matching Host)";
    case 404: return "Not found";
    case 405: return "Method not allowed";
    case 411: return "Content-Length required (no Transfer-Encoding)";
    case 413: return "Body larger than --max-body, or output_too_large (--max-output-values, --max-image-pixels)";
    case 415: return "Body is not JSON, or is compressed";
    case 406: return "Accept names only text/event-stream, which a POST route does not send (JSON or NDJSON)";
    case 416: return "More than one byte range";
    case 422: return "Valid JSON, impossible request";
    case 429: return "This client address already runs its share of long requests (half of --max-streams)";
    case 431: return "More than 100 header fields";
    case 503: return "Over capacity, draining, or renderer unavailable";
    case 504: return "Deadline passed (--request-timeout; --sweep-timeout for sweeps and heatmaps)";
    default: return "Error";
  }
}

// A stable name a generated client calls the route by: the path after /api/v1/ in lower camel case
// ("work-precision" -> workPrecision, "render/frames" -> renderFrames), with "Get" for the GET form of a path that
// also takes POST; the service's own paths by their name (livez, openapi, dashboard).
std::string operation_id(const RouteSpec& r) {
  static const std::string kApi = "/api/v1/";
  if (r.path == "/") return "dashboard";
  std::string path = r.path.rfind(kApi, 0) == 0 ? r.path.substr(kApi.size()) : r.path.substr(1);
  path = path.substr(0, path.find('.'));  // openapi.json -> openapi
  std::string id;
  bool upper = false;
  for (char ch : path) {
    if (ch == '/' || ch == '-') {
      upper = true;
      continue;
    }
    id += upper ? static_cast<char>(std::toupper(static_cast<unsigned char>(ch))) : ch;
    upper = false;
  }
  const bool has_post = std::any_of(route_table().begin(), route_table().end(),
                                    [&](const RouteSpec& o) { return o.path == r.path && o.method == "POST"; });
  return r.method == "GET" && has_post ? id + "Get" : id;
}

// The group a route is listed under: compute (solves, maps, integration), render (pictures) or service.
std::string tag_of(const std::string& path) {
  if (path.rfind("/api/v1/render/", 0) == 0) return "render";
  if (path.rfind("/api/v1/version", 0) == 0 || path.rfind("/api/v1/", 0) != 0) return "service";
  return "compute";
}

// The records a streaming route sends: SolveResult's route streams SolveStreamRecord, and so on.
std::string stream_schema(const RouteSpec& r) {
  const std::string& result = r.result_schema;
  if (result.size() > 12 && result.compare(result.size() - 12, 12, "StreamRecord") == 0) return result;
  return result.substr(0, result.size() - std::string("Result").size()) + "StreamRecord";
}

// The request schema of a route of the field table.
const char* request_schema_of(fields::Route route) {
  switch (route) {
    case fields::solve: return "SolveRequest";
    case fields::sweep: return "SweepRequest";
    case fields::basins: return "BasinRequest";
    case fields::integrate: return "IntegrateRequest";
    case fields::work_precision: return "WorkPrecisionRequest";
    default: return "";
  }
}

// The render route of a path below /api/v1/render/, else nullptr.
const RenderRoute* render_route_of(const std::string& path) {
  static const std::string kRender = "/api/v1/render/";
  return path.rfind(kRender, 0) == 0 ? find_render_route(path.substr(kRender.size())) : nullptr;
}

// Query parameters of a GET form: one per field the route reads (see query_params.hpp), in the codec's words: its
// own schema's properties (a render's picture options), then a render's base request (render_routes(): a solve's,
// an integration's too where it draws one).
json query_parameters(const json& all_schemas, const RouteSpec& route) {
  json params = json::array();
  std::set<std::string> named;
  // A parameter has its field's schema: a number, string or boolean as such, a list of them comma-separated (or
  // as [..]); an object, a matrix or a list of objects as JSON text.
  auto add = [&](const json& s) {
    if (!s.contains("properties")) return;
    for (const auto& [name, field] : s["properties"].items()) {
      if (!named.insert(name).second) continue;
      const auto plain = [](const json& t) {
        return !t.contains("$ref") && t.value("type", "") != "object" && t.value("type", "") != "array";
      };
      const bool list = field.value("type", "") == "array" && plain(field["items"]);
      json p{{"name", name}, {"in", "query"}, {"required", false}, {"description", field.value("description", "")}};
      if (plain(field) || list) {
        p["schema"] = field;
        if (list) p["style"] = "form", p["explode"] = false;
      } else {
        p["content"] = {{"application/json", {{"schema", field}}}};
        p["description"] = p["description"].get<std::string>() + (p["description"] == "" ? "" : " ") + "(as JSON text)";
      }
      params.push_back(std::move(p));
    }
  };
  add(all_schemas[route.request_schema]);
  const RenderRoute* render = render_route_of(route.path);
  if (!render) return params;
  json base = all_schemas[request_schema_of(render->base)];
  if (render->picture == fields::render_residuals) {  // one solve per method x differential: the lists choose them
    base["properties"].erase("method");
    base["properties"].erase("differential");
  }
  add(base);
  if (render->integrations_too) add(all_schemas[request_schema_of(fields::integrate)]);
  return params;
}

// The schema with every $ref replaced by the schema it names, titled by that name. A request body's schema is
// written out in full: openapi-typescript (at its defaults) types a property with a default as always present in a
// components schema, as a response carries it, but as optional inside a requestBody, as a request may leave it out.
json written_out(const json& s, const json& all_schemas) {
  if (s.is_array()) {
    json out = json::array();
    for (const json& item : s) out.push_back(written_out(item, all_schemas));
    return out;
  }
  if (!s.is_object()) return s;
  if (s.contains("$ref")) {
    const std::string name = s["$ref"].get<std::string>().substr(std::string("#/components/schemas/").size());
    json out = written_out(all_schemas.at(name), all_schemas);
    out["title"] = name;
    return out;
  }
  json out = json::object();
  for (const auto& [key, value] : s.items()) out[key] = written_out(value, all_schemas);
  return out;
}

}  // namespace

std::string openapi_document(const ServerOptions& options) {
  const json all = schemas();
  json paths = json::object();
  for (const auto& r : route_table()) {
    json op{{"operationId", operation_id(r)}, {"summary", r.summary}, {"tags", json::array({tag_of(r.path)})}};
    if (!r.request_schema.empty()) {
      if (r.method == "POST") {
        json media{{"schema", written_out(ref(r.request_schema), all)}};
        if (const json examples = request_examples(r.request_schema); !examples.empty()) media["examples"] = examples;
        op["requestBody"] = {{"required", true}, {"content", {{"application/json", media}}}};
      } else {
        op["parameters"] = query_parameters(all, r);
      }
    }
    json content = json::object();
    const std::string stream_name = stream_schema(r);
    for (const auto& type : r.success_types) {
      json media = json::object();
      if (type == "application/json" && !r.result_schema.empty()) media["schema"] = ref(r.result_schema);
      else if (type == "application/x-ndjson" || type == "text/event-stream") media["schema"] = ref(stream_name);
      else if (type == "image/png" || type == "image/webp") media["schema"] = {{"type", "string"}, {"format", "binary"}};
      else media["schema"] = {{"type", "string"}};
      content[type] = media;
    }
    op["responses"]["200"] = {{"description", "OK"}, {"content", content}};
    const bool png = std::find(r.success_types.begin(), r.success_types.end(), "image/png") != r.success_types.end();
    if (r.method == "GET" && png) {
      // GET renders carry a validator (server/http_validators.hpp): a repeated request answers 304 undrawn.
      op["responses"]["200"]["headers"]["ETag"] = {
          {"description", "W/\"hash of the build, the route and the canonical request\"; send it back as If-None-Match"},
          {"schema", {{"type", "string"}}}};
      op["responses"]["304"] = {{"description", "Not Modified: If-None-Match named this request's ETag; nothing was drawn"}};
    }
    const RenderRoute* render = render_route_of(r.path);
    if (render && (render->integrations_too || render->base == fields::integrate))  // it draws an integration
      op["responses"]["200"]["headers"][kWarningsHeader] = {
          {"description", "present when the picture draws an integration whose result has warnings: their codes "
                          "(IntegrateResult.warnings), comma-separated; a picture cannot say them"},
          {"schema", {{"type", "string"}}}};
    for (int status : r.errors) {
      op["responses"][std::to_string(status)] = {{"description", status_text(status)},
                                                 {"content", {{"application/json", {{"schema", ref("Error")}}}}}};
    }
    std::string method = r.method;
    for (auto& c : method) c = static_cast<char>(c - 'A' + 'a');
    paths[r.path][method] = op;
  }
  json doc{{"openapi", "3.0.3"},
           {"info", {{"title", "lienewton"}, {"version", LIENEWTON_VERSION},
                     {"description", "Newton's method on Lie groups (Owren & Welfert): solves, stability sweeps, "
                                     "implicit integrators, work-precision data and renders. Errors are "
                                     "{\"error\":{\"code\",\"field\",\"message\"}}."}}},
           {"tags", json::array({json{{"name", "compute"}, {"description", "solves, stability and basin maps, integration, work-precision"}},
                                 json{{"name", "render"}, {"description", "pictures of the same requests (PNG or SVG)"}},
                                 json{{"name", "service"}, {"description", "health, metrics, version, this document, the dashboard"}}})},
           // Relative: the document describes the server that sends it; the second entry is for a saved copy.
           {"servers", json::array({json{{"url", "/"}, {"description", "the server that sent this document"}},
                                    json{{"url", "http://{host}:{port}"}, {"description", "a server by address"},
                                         {"variables", {{"host", {{"default", "localhost"}}},
                                                        {"port", {{"default", std::to_string(options.port)}}}}}}})},
           {"paths", paths},
           {"components", {{"schemas", all}}},
           {"x-lienewton", openapi_labels(options)}};
  return doc.dump(1, ' ', false, json::error_handler_t::replace);
}

}  // namespace lienewton::service
