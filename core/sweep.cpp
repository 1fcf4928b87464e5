#include "sweep.hpp"

#include <algorithm>
#include <chrono>
#include <numeric>
#include <cmath>
#include <atomic>
#include <mutex>
#include <sstream>

#include "byte_buffer.hpp"
#include "group_registry.hpp"
#include "parallel_for.hpp"
#include "problems.hpp"
#include "validation.hpp"

namespace lienewton {
namespace {

constexpr std::size_t kMaxCells = 100000;

std::vector<int> paper_dimensions() {
  std::vector<int> n;
  for (int i = 2; i <= 15; ++i) n.push_back(i);
  return n;
}
// The paper's N, or the one n the problem (rigid-body, heavy-top, stiff-body) or its group (SE(3), SO(3) x R^3) is written
// for: there the map sweeps h alone.
std::vector<int> default_dimensions(const ProblemSpec& problem) {
  std::optional<int> only = problem.family().only_index();
  if (!only && !problem.g) only = required_index(problem.kind);
  return only ? std::vector<int>{*only} : paper_dimensions();
}
std::vector<double> paper_step_sizes() {
  std::vector<double> h;
  for (int e = -10; e <= 10; ++e) h.push_back(std::ldexp(1.0, e));
  return h;
}

// Cells differ ~100x in cost, mostly by N (an iteration costs O(N^3) exact, O(N^5) by finite differences):
// claim the largest N first so both cores stay busy to the end. Ties keep grid order: the schedule is fixed.
std::vector<int> largest_n_first(const SweepRequest& req) {
  const std::size_t per_method = req.n.size() * req.h.size();
  std::vector<int> order(req.methods.size() * per_method);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return req.n[(static_cast<std::size_t>(a) % per_method) / req.h.size()] >
           req.n[(static_cast<std::size_t>(b) % per_method) / req.h.size()];
  });
  return order;
}

// The spec of the cells at dimension n: the sweep's problem, started at start_point(n, seed).
ProblemSpec at_dimension(const ProblemSpec& problem, int n) {
  ProblemSpec cell = problem;
  cell.n = n;
  cell.z.reset();
  return cell;
}

// 422 naming `field` when a value of the list appears twice.
template <class T>
void refuse_repeats(const std::vector<T>& list, const char* field) {
  std::vector<T> sorted = list;
  std::sort(sorted.begin(), sorted.end());
  const auto twice = std::adjacent_find(sorted.begin(), sorted.end());
  if (twice == sorted.end()) return;
  std::ostringstream value;
  value << *twice;
  validation::unprocessable(field, std::string(field) + " lists " + value.str() + " more than once: give each value once");
}

// A cell as bytes for a WorkFarm, every double bit for bit.
std::string to_bytes(const SweepCell& c) {
  ByteWriter out;
  out.put(c.method).put(c.n).put(c.h).put(c.status).put_string(c.reason).put(c.iterations).put(c.rate.has_value());
  out.put(c.rate.value_or(0.0)).put(c.residual).put(c.seconds);
  return out.take();
}
SweepCell cell_from_bytes(const std::string& bytes) {
  ByteReader in(bytes);
  SweepCell c;
  c.method = in.get<Method>();
  c.n = in.get<int>();
  c.h = in.get<double>();
  c.status = in.get<Status>();
  c.reason = in.get_string();
  c.iterations = in.get<int>();
  const bool has_rate = in.get<bool>();
  const double rate = in.get<double>();
  if (has_rate) c.rate = rate;
  c.residual = in.get<double>();
  c.seconds = in.get<double>();
  return c;
}

}  // namespace

SweepRequest with_defaults(SweepRequest req) {
  if (req.n.empty()) req.n = default_dimensions(req.problem);
  if (req.h.empty()) req.h = paper_step_sizes();
  return req;
}

void validate(const SweepRequest& request) {
  const SweepRequest req = with_defaults(request);
  // The checks of the lists first: each n's problem costs a compilation of g and an evaluation.
  if (req.methods.empty()) validation::invalid("methods", "methods must name at least one method");
  for (double h : req.h) validation::check(fields::h, h, "h");
  // A repeated n or h would compute the same cells twice (and each n's program once more).
  refuse_repeats(req.n, "n");
  refuse_repeats(req.h, "h");
  if (req.methods.size() * req.n.size() * req.h.size() > kMaxCells)
    validation::invalid("h", "the grid has more than " + std::to_string(kMaxCells) + " cells");
  if (req.threads < 0) validation::invalid("threads", "threads must be >= 0");
  if (req.shard && !(req.shard->count >= 1 && req.shard->index >= 0 && req.shard->index < req.shard->count))
    validation::invalid("shard", "shard must have count >= 1 and 0 <= index < count");
  validate(req.solver);
  for (Method m : req.methods) check_globalization(m, req.solver);
  // Each n's cells run on up to `threads` threads at once, each with its own workspace for g.
  const double cells = double(req.methods.size()) * double(req.h.size());
  const int threads = static_cast<int>(std::min(double(resolve_thread_count(req.threads)), std::max(cells, 1.0)));
  for (int n : req.n) validate(at_dimension(req.problem, n), threads);
}

std::vector<int> shard_cells(const SweepRequest& request, const Shard& shard) {
  const SweepRequest req = with_defaults(request);
  std::vector<int> mine;
  const std::vector<int> order = largest_n_first(req);
  for (std::size_t k = static_cast<std::size_t>(shard.index); k < order.size(); k += static_cast<std::size_t>(shard.count))
    mine.push_back(order[k]);
  return mine;
}

SweepResult sweep(const SweepRequest& request, const CellCallback& on_cell,
                  const std::function<bool()>& should_continue, const WorkFarm* farm) {
  validate(request);
  return sweep_validated(request, on_cell, should_continue, farm);
}

SweepResult sweep_validated(const SweepRequest& request, const CellCallback& on_cell,
                            const std::function<bool()>& should_continue, const WorkFarm* farm) {
  const SweepRequest req = with_defaults(request);
  const auto start = std::chrono::steady_clock::now();
  std::vector<ProblemSpec> problems;  // one per N, its z shared by all methods and h: the paper's setup
  for (int n : req.n) {
    problems.push_back(at_dimension(req.problem, n));
    // heavy-top's, stiff-body's and chain's start is their parameters' state, which they refuse to be given as z.
    if (problems.back().g || !starts_from_parameters(problems.back().kind)) problems.back().z = problems.back().start();
  }

  const std::size_t per_method = req.n.size() * req.h.size();
  SweepResult result;
  result.cells.resize(req.methods.size() * per_method);
  std::vector<char> done(result.cells.size(), 0);
  std::mutex callback_mutex;
  std::atomic<bool> cancelled{false};
  // Polled every iteration of every cell, so a cancelled sweep stops within one iteration.
  const TraceCallback poll = [&](const TraceRecord&) {
    if (!cancelled && should_continue && !should_continue()) cancelled = true;
    return !cancelled.load();
  };
  // Cell i of the grid (method-major, then n, then h); nullopt when the sweep was cancelled during it.
  const auto solve_cell = [&](std::size_t i) -> std::optional<SweepCell> {
    const std::size_t m = i / per_method, ni = (i % per_method) / req.h.size(), hi = i % req.h.size();
    SolveRequest s{problems[ni], req.solver, req.h[hi]};
    s.solver.method = req.methods[m];
    s.solver.include_iterates = false;
    s.solver.timed = false;  // a cell keeps no trace: its per-iteration CPU clock reads (3 syscalls)
                             // were 5 % of an exact sweep in perf
    // validate(req) checked every cell's fields: the cell's solve does not check (nor evaluate g) again.
    const SolveResult r = s.problem.family().solve(s, poll);
    if (r.status == Status::cancelled) return std::nullopt;
    return SweepCell{s.solver.method, s.problem.n, s.h, r.status, r.reason, r.total_iterations(), r.rate, r.residual, r.seconds};
  };
  // Files a finished cell in its grid slot (any order, any thread or process) and reports it.
  const auto file_cell = [&](std::size_t i, SweepCell&& cell) {
    result.cells[i] = std::move(cell);
    done[i] = 1;
    if (!on_cell) return true;
    std::lock_guard lock(callback_mutex);
    if (!on_cell(result.cells[i])) cancelled = true;
    return !cancelled.load();
  };
  // The cells to compute, in claim order: all of them, or this shard's.
  const std::vector<int> order = req.shard ? shard_cells(req, *req.shard) : largest_n_first(req);
  if (farm) {
    const auto compute = [&](int i) {
      const std::optional<SweepCell> cell = solve_cell(static_cast<std::size_t>(i));
      return cell ? to_bytes(*cell) : std::string();
    };
    const auto deliver = [&](int i, const std::string& bytes) {
      return !bytes.empty() && file_cell(static_cast<std::size_t>(i), cell_from_bytes(bytes));
    };
    if (!farm->run(order, compute, deliver)) return {};  // a process that only computed cells for the farm
  } else {
    parallel_for(static_cast<int>(order.size()), req.threads, [&](int k) {
      const std::size_t i = static_cast<std::size_t>(order[static_cast<std::size_t>(k)]);
      std::optional<SweepCell> cell = solve_cell(i);
      return cell && file_cell(i, std::move(*cell));
    });
  }
  // A cancelled sweep returns the cells that finished, still in grid order.
  std::vector<SweepCell> finished;
  for (std::size_t i = 0; i < result.cells.size(); ++i)
    if (done[i]) {
      finished.push_back(std::move(result.cells[i]));
      if (req.shard) result.cell_indices.push_back(i);
    }
  result.grid_cells = result.cells.size();
  result.shard = req.shard;
  result.cells = std::move(finished);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

SweepResult merge_shards(const std::vector<SweepResult>& parts) {
  if (parts.empty() || !parts.front().shard) validation::invalid("shard", "merge needs the results of a sharded sweep");
  const int count = parts.front().shard->count;
  const std::size_t grid = parts.front().grid_cells;
  std::vector<char> have_part(static_cast<std::size_t>(count), 0);
  std::vector<std::optional<SweepCell>> cells(grid);
  SweepResult merged;
  for (const SweepResult& part : parts) {
    if (!part.shard) validation::invalid("shard", "a result without shard is not part of a sharded sweep");
    if (part.shard->count != count || part.grid_cells != grid)
      validation::invalid("shard", "the results come from different shardings or grids");
    const int index = part.shard->index;
    if (index < 0 || index >= count) validation::invalid("shard", "shard index out of range");
    if (have_part[static_cast<std::size_t>(index)]++)
      validation::invalid("shard", "shard " + std::to_string(index) + " is given twice");
    if (part.cell_indices.size() != part.cells.size())
      validation::invalid("shard", "shard " + std::to_string(index) + " has a cell index per cell missing");
    for (std::size_t k = 0; k < part.cells.size(); ++k) {
      const std::size_t i = part.cell_indices[k];
      if (i >= grid || cells[i]) validation::invalid("shard", "cell " + std::to_string(i) + " is out of range or repeated");
      cells[i] = part.cells[k];
    }
    merged.seconds += part.seconds;
  }
  for (int i = 0; i < count; ++i)
    if (!have_part[static_cast<std::size_t>(i)])
      validation::invalid("shard", "shard " + std::to_string(i) + " of " + std::to_string(count) + " is missing");
  for (std::size_t i = 0; i < grid; ++i) {
    if (!cells[i]) validation::invalid("shard", "cell " + std::to_string(i) + " is in no shard (a part stopped early)");
    merged.cells.push_back(std::move(*cells[i]));
  }
  merged.grid_cells = grid;
  return merged;
}

}  // namespace lienewton
