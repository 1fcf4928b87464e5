#pragma once
// The compute commands, one table, and the one path that runs them: a request document is read and validated
// into a PreparedRequest, which run_prepared runs to the result's JSON. The HTTP routes, the CLI and the Python
// module all go through it, so that they answer a request alike; what differs between them (streams, progress,
// metrics, deadlines, MPI ranks) comes in through RunHooks.
#include <cstddef>
#include <functional>
#include <optional>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "core/basins.hpp"
#include "core/cancellation.hpp"
#include "core/fields.hpp"
#include "core/integrate.hpp"
#include "core/solve.hpp"
#include "core/sweep.hpp"
#include "core/work_farm.hpp"
#include "core/work_precision.hpp"
#include "server/json_codec.hpp"

namespace lienewton::service {

enum class Command { solve, sweep, basins, integrate, work_precision };

// One row per command: the list the CLI's commands, Python's functions and the field help are read from.
struct CommandSpec {
  Command command;
  const char* name;      // as the CLI and Python spell it; its route is POST /api/v1/<name>
  fields::Route fields;  // the request fields it takes
  bool is_map;           // a map of many solves (sweep, basins): --sweep-timeout, and spread over MPI ranks
  const char* summary;   // what its route does (OpenAPI), and what it streams
  const char* request_schema;  // the OpenAPI schemas of its request and result
  const char* result_schema;
};
const std::vector<CommandSpec>& command_table();
// By name ("work_precision" too, as Python spells it); nullptr for none.
const CommandSpec* find_command(std::string_view name);
const CommandSpec& command_spec(Command command);

struct OutputLimits;

// A request read from its document and validated (an integration's defaults resolved), with the server's output
// caps applied where it has them (server/output_limits.hpp): the one argument run_prepared takes, so nothing runs
// an unchecked request.
class PreparedRequest {
 public:
  Command command() const { return static_cast<Command>(request_.index()); }
  // f(the request), whichever of the five it is.
  template <class F>
  decltype(auto) visit(F&& f) const { return std::visit(std::forward<F>(f), request_); }

 private:
  // In Command's order.
  using Request = std::variant<SolveRequest, SweepRequest, BasinRequest, IntegrateRequest, WorkPrecisionRequest>;
  explicit PreparedRequest(Request request) : request_(std::move(request)) {}
  Request request_;
  friend PreparedRequest prepare_request(Command, const json&, const Limits&);
  friend void apply_output_limits(PreparedRequest&, const OutputLimits&);
};

// Reads and validates (throws RequestError naming the field). Compiles and evaluates a user's program: the server
// calls it under the request's work slot and deadline.
PreparedRequest prepare_request(Command command, const json& body, const Limits& limits);

// How the caller follows the work. Each hook is optional; one that returns false stops the work, and
// run_prepared then throws Cancelled.
struct RunHooks {
  // Once before the work of a command that counts items: its unit ("cells", "rows", "steps", "series") and their
  // number (0 when not known ahead).
  std::function<void(std::string_view unit, std::size_t total)> begin;
  // After each item (a solve's iteration, a cell, a row, a step, a series), from any thread, with its index.
  std::function<bool(std::size_t index)> step;
  // Each record the service's stream of the command sends, by type ("iteration", "path_point", "cell", "grid",
  // "row", "step", "series"), in order; records are only made when this is set. With it a basin map's result is
  // its summary: its rows were the records.
  std::function<bool(std::string_view type, json record)> record;
  // Each solve that finished (a solve, a sweep's cell, a basin map's pixel): its status and iterations.
  std::function<void(Status status, int iterations)> solved;
  // Spreads sweep cells and basin rows over the ranks of an MPI job.
  const WorkFarm* farm = nullptr;
};

// Runs the request to its result document. Throws Cancelled when a hook stopped it or the thread's cancellation
// token did (a solve, an integration or a basin map that ended cancelled).
json run_prepared(const PreparedRequest& request, const RunHooks& hooks = {});

// prepare_request then run_prepared (no output caps): the CLI's and Python's path.
json run_request(Command command, const json& body, const Limits& limits, const RunHooks& hooks = {});

}  // namespace lienewton::service
