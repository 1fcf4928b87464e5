#pragma once
// The compute commands run on a request document: the JSON body in, the result's JSON out, through the codec's
// checks. The one path of the CLI and the Python module, so that both answer a request alike.
#include <cstddef>
#include <functional>
#include <optional>
#include <string_view>

#include "core/work_farm.hpp"
#include "server/json_codec.hpp"

namespace lienewton::service {

enum class Command { solve, sweep, basins, integrate, work_precision };

// "solve", "sweep", "basins", "integrate", "work-precision" (also "work_precision").
std::optional<Command> command_from_string(std::string_view name);

// How far a long command has got: begin(unit, total) once before the work ("cells", "rows", "steps", "series";
// total 0 when not known ahead), then step() per item done, from any thread. farm: spreads sweep cells and basin
// rows over the ranks of an MPI job.
struct RunHooks {
  std::function<void(std::string_view unit, std::size_t total)> begin;
  std::function<void()> step;
  const WorkFarm* farm = nullptr;
  // Each record the service's stream of the command sends, by type ("iteration", "path_point", "cell", "grid",
  // "row", "step", "series"), in order; the records are only made when this is set. With it a basin map's result
  // is its summary: its rows were the records.
  std::function<void(std::string_view type, const json& record)> record;
};

// Reads the request (throws RequestError naming the field), runs it and returns the result document. Work under
// a CancellationScope stops early when its token is cancelled.
json run_request(Command command, const json& body, const Limits& limits, const RunHooks& hooks = {});

}  // namespace lienewton::service
