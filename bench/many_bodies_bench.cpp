// Many bodies: the built-in chain (k links on (SE(3) x R^6)^k joined by stiff penalty joints) at its default data
// and a fixed step, for k = 2, 4, ..., 128 bodies, each integrator timed in the same run:
//   Chain_Scaling/<integrator>   per k the mean Newton iterations per step, the CPU per step and the peak heap
//                                of the default integration (t = 0 ... 1, 256 steps); the counters give the iterations' max over min across k, the
//                                exponent of the CPU per step fitted on k = 8 ... 128 (least squares on log-log) and
//                                the peak heap's likewise; the label says whether the iterations per step stay at
//                                most 4 and within 1.5x across k. Errors out when an integration fails.
//   Chain_DenseVsSparse/<k>      its first 8 steps with the Newton matrix factored dense (LU on the dense
//                                matrix) and structured (the automatic choice: sparse LU), same run: dense_over_sparse
//                                is their CPU ratio, and both must land on the same y (to 1e-10 relative).
//   Chain_Adaptive/<k>           rkmk-radau3 with adaptive steps (rtol = atol = 1e-6) over t = 0 ... 0.05 on k links:
//                                accepted steps, rejected tries and the CPU per accepted step (the stiffness test
//                                that picks the error estimate is part of every try).
//   Program_DerivativeOnBodies   dg_y's matrix of a user's program (g = 0*y) on (SE(3) x R^6)^k, k = 8, 32, 90:
//                                per k the peak heap of one dg_matrix, the program's reported workspace and their
//                                ratio; heap_exponent is the peak's fitted on k, matrix_exponent the peak's in units
//                                of the (11k)^2 entries of the one matrix the program reads (0: the derivative costs
//                                a fixed number of those matrices, however many its 12k directions).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "bench/alloc_count.hpp"
#include "core/cpu_clock.hpp"
#include "core/group_registry.hpp"
#include "core/integrate.hpp"
#include "core/order_fit.hpp"
#include "core/solvers/newton_step.hpp"
#include "core/user_field/user_vector_field.hpp"

namespace {

using namespace lienewton;

constexpr double kStep = 1.0 / 256;  // the chain's default joint period is ~0.02 s: h spans about half of one
constexpr int kScalingSteps = 256;   // the default t_end = 1: the first step's start-up (a stage from rest, whose
                                     // explicit prediction is too far off to accept) weighs as in a user's run
constexpr int kDenseSteps = 8;       // dense LU at k = 128 costs seconds per step

ProblemSpec chain(int k) { return ProblemSpec{.kind = ProblemKind::chain, .group = "SExR^k", .n = k}; }

// dense: every Newton matrix factored dense (the bound on sparse LU lifted past the system's size).
IntegrateResult run(int k, Integrator integrator, int steps, bool dense = false) {
  IntegrateRequest req{.problem = chain(k), .h = kStep, .t_end = steps * kStep, .integrator = integrator,
                       .reference = false};
  const int bound = dense_lu_max_dim();
  if (dense) dense_lu_max_dim() = std::numeric_limits<int>::max();
  IntegrateResult r = group_family("SExR^k").integrate(req, req.problem.start(), {});
  dense_lu_max_dim() = bound;
  return r;
}

void Chain_Scaling(benchmark::State& state, Integrator integrator) {
  const std::vector<int> bodies{2, 4, 8, 16, 32, 64, 128};
  std::vector<double> cpu(bodies.size(), 0.0), iterations(bodies.size()), peak(bodies.size());
  for (auto _ : state) {
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      IntegrateResult r;
      const double start = thread_cpu_seconds();
      peak[i] = static_cast<double>(bench::peak_bytes_in([&] { r = run(bodies[i], integrator, kScalingSteps); }));
      cpu[i] += thread_cpu_seconds() - start;
      if (r.status != Status::converged)
        state.SkipWithError(("k = " + std::to_string(bodies[i]) + ": " + r.reason).c_str());
      iterations[i] = r.mean_iterations;
    }
  }
  std::vector<double> ks, per_step, heap;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const std::string k = std::to_string(bodies[i]);
    state.counters["iterations_k" + k] = iterations[i];
    state.counters["cpu_per_step_us_k" + k] = 1e6 * cpu[i] / (double(state.iterations()) * kScalingSteps);
    state.counters["peak_heap_kib_k" + k] = peak[i] / 1024;
    if (bodies[i] >= 8) ks.push_back(bodies[i]), per_step.push_back(cpu[i]), heap.push_back(peak[i]);
  }
  const auto [low, high] = std::minmax_element(iterations.begin(), iterations.end());
  state.counters["iterations_max_over_min"] = *high / *low;
  state.counters["cpu_exponent"] = fitted_order(ks, per_step).value_or(NAN);
  state.counters["heap_exponent"] = fitted_order(ks, heap).value_or(NAN);
  state.SetLabel(*high <= 4 && *high <= 1.5 * *low ? "iterations per step at most 4 and flat in k"
                                                     : "iterations per step above 4 or not flat in k");
}

void Chain_DenseVsSparse(benchmark::State& state, Integrator integrator) {
  const int k = static_cast<int>(state.range(0));
  double dense = 0, sparse = 0;
  IntegrateResult a, b;
  for (auto _ : state) {
    double start = thread_cpu_seconds();
    a = run(k, integrator, kDenseSteps, true);
    dense += thread_cpu_seconds() - start;
    start = thread_cpu_seconds();
    b = run(k, integrator, kDenseSteps);
    sparse += thread_cpu_seconds() - start;
  }
  if (a.status != Status::converged || b.status != Status::converged) state.SkipWithError("a run failed");
  if (!((a.y - b.y).norm() <= 1e-10 * b.y.norm())) state.SkipWithError("dense and sparse land apart");
  state.counters["dense_over_sparse"] = dense / sparse;
  state.SetLabel(std::string(to_string(a.linear_solver.value_or(Factorization::gmres))) + " vs " +
                 std::string(to_string(b.linear_solver.value_or(Factorization::gmres))));
}

void Chain_Adaptive(benchmark::State& state) {
  const int k = static_cast<int>(state.range(0));
  IntegrateRequest req{.problem = chain(k), .h = kStep, .t_end = 0.05, .integrator = Integrator::rkmk_radau3,
                       .reference = false, .rtol = 1e-6, .atol = 1e-6};
  IntegrateResult r;
  double cpu = 0;
  for (auto _ : state) {
    const double start = thread_cpu_seconds();
    r = group_family("SExR^k").integrate(req, req.problem.start(), {});
    cpu += thread_cpu_seconds() - start;
  }
  if (r.status != Status::converged) state.SkipWithError(r.reason.c_str());
  const double steps = static_cast<double>(r.steps.size());
  state.counters["steps"] = steps;
  state.counters["rejected"] = r.rejected;
  state.counters["cpu_per_step_ms"] = 1e3 * cpu / (double(state.iterations()) * steps);
}

void Program_DerivativeOnBodies(benchmark::State& state) {
  const std::vector<int> bodies{8, 32, 90};  // 90: the most bodies a program takes (10^6 entries per value)
  std::vector<double> ks, peak, per_matrix;
  for (auto _ : state) {
    ks.clear(), peak.clear(), per_matrix.clear();
    for (int k : bodies) {
      const SE3xR6PowerGroup group(k);
      const auto program = user_field::compile("g = 0*y", 11 * k, {});
      const UserVectorField<SE3xR6PowerGroup> field(group, program);
      const SE3xR6PowerGroup::Element y = group.random(3);
      double zero = 0;
      const double bytes = static_cast<double>(bench::peak_bytes_in([&] { zero = field.dg_matrix(group, y).norm(); }));
      if (zero != 0) state.SkipWithError("the derivative of 0*y is not 0");
      const double reported = program->workspace_bytes(group.dim());
      const std::string name = std::to_string(k);
      state.counters["peak_heap_kib_k" + name] = bytes / 1024;
      state.counters["reported_kib_k" + name] = reported / 1024;
      state.counters["peak_over_reported_k" + name] = bytes / reported;
      ks.push_back(k), peak.push_back(bytes), per_matrix.push_back(bytes / (121.0 * k * k * sizeof(double)));
    }
  }
  state.counters["heap_exponent"] = fitted_order(ks, peak).value_or(NAN);
  state.counters["matrix_exponent"] = fitted_order(ks, per_matrix).value_or(NAN);
}

}  // namespace

BENCHMARK(Chain_Adaptive)->Arg(8)->Arg(32)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(Program_DerivativeOnBodies)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(Chain_Scaling, dirk_cg2, Integrator::dirk_cg2)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(Chain_Scaling, rkmk_radau3, Integrator::rkmk_radau3)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(Chain_DenseVsSparse, dirk_cg2, Integrator::dirk_cg2)
    ->Arg(8)->Arg(128)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_CAPTURE(Chain_DenseVsSparse, rkmk_radau3, Integrator::rkmk_radau3)
    ->Arg(8)->Arg(128)->Unit(benchmark::kMillisecond)->Iterations(1);
