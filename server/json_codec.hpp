#pragma once
// JSON <-> core request/result model: the one place where the API's field names live. Every request field is
// type- and range-checked here, before the core sees it; the core's validate() then checks the semantics.
#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "core/basins.hpp"
#include "core/integrate.hpp"
#include "core/request_error.hpp"
#include "core/solve.hpp"
#include "core/sweep.hpp"
#include "core/work_precision.hpp"

namespace lienewton::service {

using nlohmann::json;

// Caps the server puts on top of the core's own rules; the CLI uses unlimited().
struct Limits {
  int max_n = 64;
  int max_iterations = 10000;
  std::size_t max_grid_cells = 5000;  // sweep: methods x n x h; work-precision: choices x h
  double max_steps = 200000;          // integrate: t_end / h; work-precision: summed over choices and h
  double max_t_end = 100;             // integrate and work-precision: the longest t_end
  int max_frames = 1000;
  int max_threads = 16;               // sweep: threads one request may ask for (0: all cores)
  static Limits unlimited();
};

// A request error with a machine-readable code: malformed_json, duplicate_field, unknown_field,
// invalid_field (all HTTP 400) or unprocessable (422, from the core).
class FieldError : public RequestError {
 public:
  FieldError(std::string code, std::string field, const std::string& message)
      : RequestError(Kind::invalid, std::move(field), message), code_(std::move(code)) {}
  const std::string& code() const { return code_; }

 private:
  std::string code_;
};

// The code a RequestError is reported with.
std::string error_code(const RequestError& error);

// Parses a request body. Rejects malformed JSON and duplicate keys (nlohmann keeps the last one silently).
json parse_body(std::string_view text);

SolveRequest solve_request_from_json(const json& body, const Limits& limits);
SweepRequest sweep_request_from_json(const json& body, const Limits& limits);
IntegrateRequest integrate_request_from_json(const json& body, const Limits& limits);
WorkPrecisionRequest work_precision_request_from_json(const json& body, const Limits& limits);
BasinRequest basin_request_from_json(const json& body, const Limits& limits);
// A sweep result as produced by to_json(SweepResult), read back (the heatmap accepts one).
SweepResult sweep_result_from_json(const json& body, const Limits& limits);
// A basin map as produced by to_json(BasinResult), read back (`lienewton merge` joins shards): grid, rows, roots,
// the methods' order, complete, seconds, shard. The summaries' counts are not read (basin_summaries recomputes
// them from the pixels).
BasinResult basin_result_from_json(const json& body);

json to_json(const PathPoint& point);
json to_json(const TraceRecord& record, bool include_iterates);
json to_json(const SolveResult& result, bool include_iterates);
json to_json(const SweepCell& cell);
json to_json(const SweepResult& result);
json to_json(const StepRecord& record);
json to_json(const IntegrateResult& result);
json to_json(const WorkPrecisionChoice& choice);
json to_json(const WorkPrecisionSeries& series);
json to_json(const WorkPrecisionResult& result);
json to_json(const BasinGrid& grid);
json to_json(const BasinRoot& root);
// A row with the roots it met first (new_roots, full objects): a stream reader can colour it at once.
json to_json(const BasinRow& row, const std::vector<BasinRoot>& roots, const std::vector<Method>& methods);
// The summary: roots, per method converged fraction, basins, mean iterations and status counts.
json basin_summary_json(const BasinResult& map);
// The whole map: {"grid", "rows", then the summary's fields}.
json to_json(const BasinResult& map, const std::vector<Method>& methods);
json matrix_to_json(const Eigen::MatrixXd& m);

json error_body(std::string_view code, std::string_view field, std::string_view message);
json error_body(const RequestError& error);

// Serialises without ever throwing on invalid UTF-8 (replaced) and without NaN/Inf (to_json writes null).
std::string dump(const json& value);
// One record of a stream (an NDJSON line without its newline, an SSE data field): {"type": type, ...record}, type
// first for people reading it, the rest in the record's order. The service's streams and `lienewton --stream`.
std::string stream_line(std::string_view type, const json& record);

}  // namespace lienewton::service
