#include "server/request_runner.hpp"

#include <atomic>
#include <stdexcept>

namespace lienewton::service {

// In Command's order: command_spec() indexes it.
const std::vector<CommandSpec>& command_table() {
  static const std::vector<CommandSpec> table{
      {Command::solve, "solve", fields::solve, false,
       "Solve y = z exp(h g(y)); streams NDJSON trace records with Accept: application/x-ndjson", "SolveRequest",
       "SolveResult"},
      {Command::sweep, "sweep", fields::sweep, true,
       "Stability map over (method, n, h); NDJSON streams one cell record per finished cell", "SweepRequest",
       "SweepResult"},
      {Command::basins, "basins", fields::basins, true,
       "Basin map: each method from every start y0 = z exp(a B1 + b B2) of a grid, each pixel classified by the root "
       "it reached or its failure; NDJSON streams a grid record, one row record per finished row, then the summary",
       "BasinRequest", "BasinResult"},
      {Command::integrate, "integrate", fields::integrate, false,
       "Time stepping with a Lie group integrator (implicit; rkmk4 explicit); NDJSON streams one step record per step",
       "IntegrateRequest", "IntegrateResult"},
      {Command::work_precision, "work-precision", fields::work_precision, false,
       "CPU time vs global error per (integrator, method, differential); NDJSON streams one series record each",
       "WorkPrecisionRequest", "WorkPrecisionResult"},
  };
  return table;
}

const CommandSpec* find_command(std::string_view name) {
  for (const CommandSpec& c : command_table())
    if (c.name == name || (name == "work_precision" && c.command == Command::work_precision)) return &c;
  return nullptr;
}

const CommandSpec& command_spec(Command command) { return command_table()[static_cast<std::size_t>(command)]; }

namespace {

template <class Request>
Request validated(Request request) {
  validate(request);
  return request;
}

}  // namespace

PreparedRequest prepare_request(Command command, const json& body, const Limits& limits) {
  switch (command) {
    case Command::solve: return PreparedRequest(validated(solve_request_from_json(body, limits)));
    case Command::sweep: return PreparedRequest(validated(sweep_request_from_json(body, limits)));
    case Command::basins: return PreparedRequest(validated(basin_request_from_json(body, limits)));
    case Command::integrate: return PreparedRequest(validated(integrate_request_from_json(body, limits)));
    case Command::work_precision: return PreparedRequest(validated(work_precision_request_from_json(body, limits)));
  }
  throw std::logic_error("prepare_request: no such command");
}

namespace {

// Runs each kind of request with the hooks; `go_on` remembers whether every hook let the work continue.
struct PreparedRun {
  const RunHooks& hooks;
  std::atomic<bool> go_on{true};

  // One item done: its progress first, then its record (made only for a stream).
  template <class MakeRecord>
  bool item(std::size_t index, std::string_view type, const MakeRecord& make) {
    if (hooks.step && !hooks.step(index)) go_on = false;
    if (hooks.record && !hooks.record(type, make())) go_on = false;
    return go_on;
  }
  void solved(Status status, int iterations) const {
    if (hooks.solved) hooks.solved(status, iterations);
  }
  void begin(std::string_view unit, std::size_t total) const {
    if (hooks.begin) hooks.begin(unit, total);
  }
  // A map's or a diagram's work ends early, without a status of its own, when a hook or the token stopped it.
  void throw_if_stopped() const {
    if (!go_on) throw Cancelled{};
    throw_if_cancelled();
  }

  json operator()(const SolveRequest& r) {
    const bool iterates = r.solver.include_iterates;
    const SolveResult result = solve_validated(r, [&](const TraceRecord& t) {
      return item(static_cast<std::size_t>(t.iteration), t.path_point ? "path_point" : "iteration",
                  [&] { return to_json(t, iterates); });
    });
    solved(result.status, result.iterations);
    if (result.status == Status::cancelled) throw Cancelled{};
    return to_json(result, iterates);
  }
  json operator()(const SweepRequest& r) {
    const SweepRequest full = with_defaults(r);
    begin("cells", r.shard ? 0 : full.methods.size() * full.n.size() * full.h.size());
    std::atomic<std::size_t> cells{0};
    const SweepResult result = sweep_validated(r, [&](const SweepCell& cell) {
      solved(cell.status, cell.iterations);
      return item(cells++, "cell", [&] { return to_json(cell); });
    }, {}, hooks.farm);
    throw_if_stopped();
    return to_json(result);
  }
  json operator()(const BasinRequest& r) {
    begin("rows", basin_shard_rows(r.size, r.shard).size());
    if (hooks.record && !hooks.record("grid", to_json(basin_grid(r)))) throw Cancelled{};
    std::size_t rows = 0;
    const BasinResult map = basins_validated(r, [&](const BasinRow& row, const std::vector<BasinRoot>& roots) {
      for (const auto& pixels : row.pixels)
        for (const BasinPixel& p : pixels) solved(p.status, p.iterations);
      return item(rows++, "row", [&] { return to_json(row, roots, r.methods); });
    }, hooks.farm);
    throw_if_stopped();  // (an MPI rank that only computed rows for rank 0 has an incomplete map of its own)
    return hooks.record ? basin_summary_json(map) : to_json(map, r.methods);
  }
  json operator()(const IntegrateRequest& r) {
    begin("steps", 0);
    const IntegrateResult result = integrate_validated(r, [&](const StepRecord& s) {
      return item(static_cast<std::size_t>(s.step), "step", [&] { return to_json(s); });
    });
    if (!go_on || result.status == Status::cancelled) throw Cancelled{};
    return to_json(result);
  }
  json operator()(const WorkPrecisionRequest& r) {
    begin("series", 0);
    std::size_t index = 0;
    const WorkPrecisionResult result = work_precision_validated(r, [&](const WorkPrecisionSeries& series) {
      return item(index++, "series", [&] { return to_json(series); });
    });
    throw_if_stopped();
    return to_json(result);
  }
};

}  // namespace

json run_prepared(const PreparedRequest& request, const RunHooks& hooks) {
  PreparedRun run{hooks};
  return request.visit(run);
}

json run_request(Command command, const json& body, const Limits& limits, const RunHooks& hooks) {
  return run_prepared(prepare_request(command, body, limits), hooks);
}

}  // namespace lienewton::service
