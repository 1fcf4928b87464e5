#include "server/request_runner.hpp"

#include <string>

namespace lienewton::service {

std::optional<Command> command_from_string(std::string_view name) {
  if (name == "solve") return Command::solve;
  if (name == "sweep") return Command::sweep;
  if (name == "basins") return Command::basins;
  if (name == "integrate") return Command::integrate;
  if (name == "work-precision" || name == "work_precision") return Command::work_precision;
  return std::nullopt;
}

json run_request(Command command, const json& body, const Limits& limits, const RunHooks& hooks) {
  const auto begin = [&](std::string_view unit, std::size_t total) {
    if (hooks.begin) hooks.begin(unit, total);
  };
  const auto step = [&] {
    if (hooks.step) hooks.step();
    return true;
  };
  const auto record = [&](std::string_view type, const auto& make) {
    if (hooks.record) hooks.record(type, make());
  };
  switch (command) {
    case Command::solve: {
      const SolveRequest r = solve_request_from_json(body, limits);
      const bool iterates = r.solver.include_iterates;
      return to_json(solve(r, [&](const TraceRecord& t) {
                       record(t.path_point ? "path_point" : "iteration", [&] { return to_json(t, iterates); });
                       return true;
                     }),
                     iterates);
    }
    case Command::sweep: {
      const SweepRequest r = sweep_request_from_json(body, limits);
      const SweepRequest full = with_defaults(r);
      begin("cells", r.shard ? 0 : full.methods.size() * full.n.size() * full.h.size());
      return to_json(sweep(r, [&](const SweepCell& cell) {
        record("cell", [&] { return to_json(cell); });
        return step();
      }, {}, hooks.farm));
    }
    case Command::basins: {
      const BasinRequest r = basin_request_from_json(body, limits);
      begin("rows", basin_shard_rows(r.size, r.shard).size());
      record("grid", [&] { return to_json(basin_grid(r)); });
      const BasinResult map = basins(r, [&](const BasinRow& row, const std::vector<BasinRoot>& roots) {
        record("row", [&] { return to_json(row, roots, r.methods); });
        return step();
      }, hooks.farm);
      return hooks.record ? basin_summary_json(map) : to_json(map, r.methods);
    }
    case Command::integrate: {
      const IntegrateRequest r = integrate_request_from_json(body, limits);
      begin("steps", 0);
      return to_json(integrate(r, [&](const StepRecord& s) {
        record("step", [&] { return to_json(s); });
        return step();
      }));
    }
    case Command::work_precision: {
      const WorkPrecisionRequest r = work_precision_request_from_json(body, limits);
      begin("series", 0);
      return to_json(work_precision(r, [&](const WorkPrecisionSeries& series) {
        record("series", [&] { return to_json(series); });
        return step();
      }));
    }
  }
  return json();
}

}  // namespace lienewton::service
