// Basin maps : two sizes, and the baseline a user would write, in one run:
//   Basins_SO3/256    256 x 256 starts x 3 methods on SO(3), paper-linear, h = 4, exact differential, all cores
//                     (target: under 2 s on 2 cores)
//   Basins_SO8/128    128 x 128 starts x 3 methods on SO(8), same problem (target: under 30 s on 2 cores)
//   BasinsBaseline_SO3/64  the same kind of map by one solve() per pixel (a SolveRequest with y0, validation and
//                     all) on one thread, then clustering every converged y against the roots: per pixel, the
//                     ratio to Basins_SO3 is the speed-up of basins() (threads included; see the label)
// Counters: pixel_solves per second (pixels x methods). Each benchmark checks its own map (every pixel
// classified, the roots' residuals below tol).
#include <benchmark/benchmark.h>

#include <Eigen/Dense>
#include <vector>

#include "core/basins.hpp"
#include "core/groups/so3.hpp"
#include "core/parallel_for.hpp"
#include "core/solve.hpp"
#include "core/start_point.hpp"

namespace {

using namespace lienewton;

BasinRequest map_request(int n, int size) {
  BasinRequest r;
  r.solve.problem.kind = ProblemKind::paper_linear;
  r.solve.problem.n = n;
  r.solve.h = 4.0;
  r.solve.solver.differential = Differential::exact;
  r.size = size;
  return r;
}

bool check(const BasinResult& map, const BasinRequest& r) {
  if (!map.complete || static_cast<int>(map.rows.size()) != r.size) return false;
  for (const BasinRoot& root : map.roots)
    if (!(root.residual <= r.solve.solver.tol)) return false;
  return true;
}

void Basins(benchmark::State& state, int n) {
  const BasinRequest r = map_request(n, static_cast<int>(state.range(0)));
  std::size_t roots = 0;
  for (auto _ : state) {
    const BasinResult map = basins(r);
    if (!check(map, r)) state.SkipWithError("basin map incomplete or a root does not solve the equation");
    roots = map.roots.size();
  }
  const double solves = static_cast<double>(r.size) * r.size * static_cast<double>(r.methods.size());
  state.counters["pixel_solves"] = benchmark::Counter(solves, benchmark::Counter::kIsIterationInvariantRate);
  state.SetLabel(std::to_string(resolve_thread_count(0)) + " threads, " + std::to_string(roots) + " roots");
}
BENCHMARK_CAPTURE(Basins, SO3, 3)->Name("Basins_SO3")->Arg(256)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(Basins, SO8, 8)->Name("Basins_SO8")->Arg(128)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

// What a user of the solve API would write: one validated solve() per pixel and method, then a linear scan of
// the roots found so far with log, on one thread.
void BasinsBaseline(benchmark::State& state) {
  const BasinRequest r = map_request(3, static_cast<int>(state.range(0)));
  const Eigen::MatrixXd z = start_point(3, r.solve.problem.seed);
  const std::vector<double> axis = basin_grid(r).axis;
  std::size_t roots_found = 0;
  for (auto _ : state) {
    std::vector<Eigen::Matrix3d> roots;
    for (int row = 0; row < r.size; ++row)
      for (int column = 0; column < r.size; ++column)
        for (Method m : r.methods) {
          SolveRequest s = r.solve;
          s.solver.method = m;
          s.y0 = Eigen::MatrixXd(z * so3::exp(Eigen::Vector3d(axis[static_cast<std::size_t>(column)],
                                                              axis[static_cast<std::size_t>(row)], 0)));
          const SolveResult res = solve(s);
          if (res.status != Status::converged) continue;
          const Eigen::Matrix3d y = res.y;
          bool known = false;
          for (const auto& root : roots) known = known || so3::log(root.transpose() * y).norm() < kRootDistance;
          if (!known) roots.push_back(y);
        }
    roots_found = roots.size();
  }
  const double solves = static_cast<double>(r.size) * r.size * static_cast<double>(r.methods.size());
  state.counters["pixel_solves"] = benchmark::Counter(solves, benchmark::Counter::kIsIterationInvariantRate);
  state.SetLabel("1 thread, " + std::to_string(roots_found) + " roots");
}
BENCHMARK(BasinsBaseline)->Name("BasinsBaseline_SO3")->Arg(64)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
