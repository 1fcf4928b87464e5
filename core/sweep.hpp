#pragma once
// A stability map: every (method, n, h) cell of a grid solved independently, in parallel, deterministically.
#include <functional>
#include <optional>
#include <vector>

#include "shard.hpp"
#include "solve.hpp"
#include "work_farm.hpp"

namespace lienewton {

// The base problem and solver options, varied over a grid: every cell is the solve of problem at one n (starting
// at start_point(n, seed); problem.n and problem.z are not used) by one of methods (solver.method is not used).
// A sweep's shard (shard.hpp) takes every count-th cell of the largest-N-first claim order, so the parts cost
// about the same.

struct SweepRequest {
  ProblemSpec problem{};
  SolverOptions solver{.differential = Differential::finite_difference};
  std::vector<Method> methods{std::begin(kAllMethods), std::end(kAllMethods)};
  std::vector<int> n;     // default: 2..15 (the paper's), or the one n of a problem or group that fixes it
  std::vector<double> h;  // default: 2^-10 .. 2^10 (21 values)
  int threads = 0;        // 0: all cores
  std::optional<Shard> shard;  // compute only this part of the grid
};

struct SweepCell {
  Method method = Method::newton_group;
  int n = 0;
  double h = 0;
  Status status = Status::max_iterations;
  std::string reason;
  int iterations = 0;
  std::optional<double> rate;
  double residual = 0;
  double seconds = 0;
};

struct SweepResult {
  std::vector<SweepCell> cells;  // ordered method-major, then n, then h (as requested), whatever the thread count
  double seconds = 0;
  // A sharded sweep: its part, the size of the whole grid, and each cell's position in it (grid order).
  std::optional<Shard> shard;
  std::size_t grid_cells = 0;
  std::vector<std::size_t> cell_indices;
};

// The grid positions (method-major, then n, then h) of the cells of `shard`, in the order they are claimed.
std::vector<int> shard_cells(const SweepRequest& request, const Shard& shard);

// Fills in the default grid where n or h are empty (the paper's; n alone where the problem or group fixes it).
SweepRequest with_defaults(SweepRequest request);
// Checks the request with its defaults (every n it will solve); throws RequestError naming the field.
void validate(const SweepRequest& request);

// Called (serialised, from worker threads) as each cell finishes; return false to cancel the rest.
using CellCallback = std::function<bool(const SweepCell&)>;
// should_continue (optional, thread-safe) is polled at every iteration of every cell: returning false
// cancels the sweep within one iteration (a client that left, a deadline). Cancelled cells are omitted.
// farm (optional): the cells are computed by its processes instead of request.threads threads here (on_cell is
// then called in the process that assembles the result); a process that only computed cells gets an empty result.
SweepResult sweep(const SweepRequest& request, const CellCallback& on_cell = {},
                  const std::function<bool()>& should_continue = {}, const WorkFarm* farm = nullptr);
// sweep() of a request the caller has already validated: it is not checked again.
SweepResult sweep_validated(const SweepRequest& request, const CellCallback& on_cell = {},
                            const std::function<bool()>& should_continue = {}, const WorkFarm* farm = nullptr);

// Joins the results of every shard of one sweep into the unsharded result: the same cells in grid order, seconds
// summed over the parts. Throws RequestError (field "shard") when a part is missing, repeated, unsharded, stopped
// early, or from another sharding of another grid.
SweepResult merge_shards(const std::vector<SweepResult>& parts);

}  // namespace lienewton
