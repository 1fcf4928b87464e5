// Large N and the per-iteration scaling, Newton Version 1 on paper-linear, h = 2^-2,
// start point seed 1:
//   LargeN_Solve/<lu|gmres>/N  a whole solve with the exact differential and a forced linear solver:
//                              dense (assemble the q x q differential, LU) vs matrix-free GMRES, N = 32, 64
//                              (both; also 8 ... 24 for the crossover) and 100 (gmres only: the dense q x q
//                              matrix alone is 196 MB there)
//   PerIteration/<exact|fd>/N  a whole solve with the automatic linear solver (lu for N <= kKrylovThreshold,
//                              gmres above), N = 3 ... 100; the counter "per_iteration" is the solve time
//                              divided by its Newton iterations (seconds, an inverted iteration-invariant rate)
// Every benchmark checks that the solve converged and records iterations, the linear solver used and the
// process' peak RSS (ru_maxrss; meaningful per benchmark only when it runs alone in its own process, as
// scripts/perf_report.sh does for the memory comparison).
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <string>

#include "core/solvers/run_method.hpp"
#include "core/solve.hpp"

namespace {

using namespace lienewton;

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux: kilobytes
}

SolveRequest large_n_request(int n, Differential differential, LinearSolver linear_solver) {
  SolveRequest req;
  req.problem.kind = ProblemKind::paper_linear;
  req.problem.n = n;
  req.h = 0.25;
  req.solver.method = Method::newton_group;
  req.solver.differential = differential;
  req.problem.seed = 1;
  req.solver.linear_solver = linear_solver;
  return req;
}

// Runs the solve once to check it and fix the iteration count, then times it.
void time_solve(benchmark::State& state, const SolveRequest& req, const char* expected_solver) {
  const SolveResult check = solve(req);
  if (check.status != Status::converged) {
    state.SkipWithError(("N = " + std::to_string(req.problem.n) + " did not converge: " + check.reason).c_str());
    return;
  }
  if (to_string(check.linear_solver) != expected_solver) {
    state.SkipWithError(("expected linear solver " + std::string(expected_solver) + ", got " +
                         std::string(to_string(check.linear_solver))).c_str());
    return;
  }
  for (auto _ : state) {
    SolveResult r = solve(req);
    benchmark::DoNotOptimize(r.residual);
  }
  state.counters["N"] = req.problem.n;
  state.counters["q"] = req.problem.n * (req.problem.n - 1) / 2;
  state.counters["iterations"] = check.iterations;
  state.counters["residual"] = check.residual;
  // Seconds per Newton iteration: iterations / time inverted.
  state.counters["per_iteration"] = benchmark::Counter(
      check.iterations, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["peak_rss_MB"] = peak_rss_mb();
  state.SetLabel(std::string(expected_solver) + ", " +
                 (req.solver.differential == Differential::exact ? "exact" : "finite-difference") +
                 ", paper-linear, newton-group, h = 2^-2, seed 1");
}

void LargeN_Solve(benchmark::State& state, LinearSolver linear_solver) {
  const int n = static_cast<int>(state.range(0));
  time_solve(state, large_n_request(n, Differential::exact, linear_solver),
             linear_solver == LinearSolver::lu ? "dense-lu" : "gmres");
}
// N = 8 ... 24 as well: where the two linear solvers cross over (compare with kKrylovThreshold).
BENCHMARK_CAPTURE(LargeN_Solve, lu, LinearSolver::lu)
    ->Arg(8)->Arg(12)->Arg(16)->Arg(24)->Arg(32)->Arg(64)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(LargeN_Solve, gmres, LinearSolver::gmres)
    ->Arg(8)->Arg(12)->Arg(16)->Arg(24)->Arg(32)->Arg(64)->Arg(100)->Unit(benchmark::kMillisecond)->UseRealTime();

void PerIteration(benchmark::State& state, Differential differential) {
  const int n = static_cast<int>(state.range(0));
  time_solve(state, large_n_request(n, differential, LinearSolver::auto_select),
             n > kKrylovThreshold ? "gmres" : "dense-lu");
}
void per_iteration_sizes(benchmark::internal::Benchmark* b) {
  for (int n : {3, 5, 8, 12, 16, 24, 32, 48, 64, 100}) b->Arg(n);
  b->Unit(benchmark::kMillisecond)->UseRealTime();
}
BENCHMARK_CAPTURE(PerIteration, exact, Differential::exact)->Apply(per_iteration_sizes);
BENCHMARK_CAPTURE(PerIteration, fd, Differential::finite_difference)->Apply(per_iteration_sizes);

}  // namespace
