// The cost of ONE iteration of each method with each differential, N = 2..15 (the paper's range) and
// 24, 32: run_method on the paper-linear implicit Euler equation (1.1) at h = 2^-2 from start_point(N, seed 1),
// with tol = 0 so that no run stops at convergence but runs until max_iterations (8) or the stagnation rule; the
// counter "per_iteration" is the run's time divided by its iterations (fixed by a check run before timing):
//   Iteration/fixed_point/N                      (1.2): one exp of h g(y) per iteration, no differential
//   Iteration/<v1|v2>/<fd|dexpinv0|dexpinv1|exact>/N  Version 1 (3.5) / Version 2 (3.20) with the differential
//                                                by finite differences (3.18), truncated dexp^-1 (3.10)/(3.11)
//                                                or exactly; dense LU at these N
// The whole experiment (1764 cells per differential) is Sweep_Lienewton/<fd|exact>/full in core_bench.cpp.
#include <benchmark/benchmark.h>

#include <string>

#include "core/groups/with_group.hpp"
#include "core/problems.hpp"
#include "core/solvers/run_method.hpp"
#include "core/start_point.hpp"

namespace {

using namespace lienewton;

constexpr int kIterations = 8;

void Iteration(benchmark::State& state, Method method, Differential differential) {
  const int n = static_cast<int>(state.range(0));
  SolverOptions options;
  options.method = method;
  options.differential = differential;
  options.tol = 0;
  options.max_iterations = kIterations;
  options.timed = false;
  with_group(n, [&](const auto& group) {
    using G = std::decay_t<decltype(group)>;
    const auto field = make_field(group, ProblemKind::paper_linear, RigidBodyParams{});
    const auto eq = Equation<G>::implicit_euler(group, typename G::Element(start_point(n, 1)), 0.25, *field);
    const SolveResult check = run_method(method, eq, options, {});
    // The check: Newton with a full differential reaches rounding in 8 iterations, the linear ones get close.
    const bool linear = method == Method::fixed_point || differential == Differential::dexpinv_0 ||
                        differential == Differential::dexpinv_1;
    if (check.iterations < 1 || !(check.residual < (linear ? 1e-3 : 1e-10))) {
      state.SkipWithError(("N = " + std::to_string(n) + ": " + check.reason).c_str());
      return;
    }
    for (auto _ : state) {
      SolveResult r = run_method(method, eq, options, {});
      benchmark::DoNotOptimize(r.residual);
    }
    state.counters["iterations"] = check.iterations;
    state.counters["per_iteration"] = benchmark::Counter(
        check.iterations, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  });
  state.SetLabel(std::string(to_string(method)) + ", " +
                 (method == Method::fixed_point ? "no differential" : std::string(to_string(differential))) +
                 ", paper-linear, h = 2^-2");
}

void sizes(benchmark::internal::Benchmark* b) {
  for (int n = 2; n <= 15; ++n) b->Arg(n);
  b->Arg(24)->Arg(32)->Unit(benchmark::kMicrosecond);
}

BENCHMARK_CAPTURE(Iteration, fixed_point, Method::fixed_point, Differential::exact)->Apply(sizes);
BENCHMARK_CAPTURE(Iteration, v1/fd, Method::newton_group, Differential::finite_difference)->Apply(sizes);
BENCHMARK_CAPTURE(Iteration, v1/dexpinv0, Method::newton_group, Differential::dexpinv_0)->Apply(sizes);
BENCHMARK_CAPTURE(Iteration, v1/dexpinv1, Method::newton_group, Differential::dexpinv_1)->Apply(sizes);
BENCHMARK_CAPTURE(Iteration, v1/exact, Method::newton_group, Differential::exact)->Apply(sizes);
BENCHMARK_CAPTURE(Iteration, v2/fd, Method::newton_algebra, Differential::finite_difference)->Apply(sizes);
BENCHMARK_CAPTURE(Iteration, v2/dexpinv0, Method::newton_algebra, Differential::dexpinv_0)->Apply(sizes);
BENCHMARK_CAPTURE(Iteration, v2/dexpinv1, Method::newton_algebra, Differential::dexpinv_1)->Apply(sizes);
BENCHMARK_CAPTURE(Iteration, v2/exact, Method::newton_algebra, Differential::exact)->Apply(sizes);

}  // namespace
