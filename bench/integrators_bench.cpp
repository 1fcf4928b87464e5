// When implicit integration pays: each integrator at the fewest steps (within 2 %)
// that reach a target global error, then all of them timed in the same run; the counters are CPU ratios against
// the first (the baseline), so a loaded machine changes every time alike.
//   Integrators_Race/rigid_body   the free rigid body, t in [0, 10], error 1e-10: dirk-cg2 against rkmk-gauss2/3
//   Integrators_Race/stiff        a stiff field on SO(3), g(y) = A - 10^4 skew(y) from y(0) = I (||h dg|| ~ 10^4 h:
//                                 the solution relaxes to exp(A / 10^4) at rate 10^4), t in [0, 1], error 1e-6:
//                                 rkmk4, which is stable only for h < 2.8e-4, against rkmk-radau2/3
//   Integrators_Race/stiff_body_kK  the built-in stiff body (spring and damper k = c = K, linearisation's eigenvalues
//                                 down to -K), t in [0, 1], error 1e-6: rkmk4 against dirk-cg2, rkmk-radau3 (exact
//                                 Newton, and the simplified Newton of dexpinv-0), rkmk-radau2 and rkmk-gauss2;
//                                 counters also give each one's mean Newton iterations per step
//   Integrators_Stiffness/K       rkmk-radau3 (dexpinv-0) at the fewest steps reaching 1e-6 on the stiff body with
//                                 k = c = K: its CPU at K over its CPU at 1e4 (stiffness independence), and rkmk4's
//                                 at K = 1e5 over 1e4
//   Integrators_AdaptiveVsFixed   one integrator with adaptive steps (rtol = atol, the largest tolerance reaching
//                                 the target error, within 5 %) against itself at the fewest equal steps reaching
//                                 it; counter fixed_over_adaptive. rigid_body_*: t in [0, 10], error 1e-10;
//                                 pulse_rkmk4: the rigid body sped up by a pulse in time, g(t, y) = s(t) g_body(y),
//                                 s = 1 + 20 exp(-((t-1)/0.1)^2), t in [0, 2], error 1e-8: equal steps must all be as
//                                 short as the pulse needs
// Every integrator's error is measured against the reference (the project's reference solution; for the stiff
// field, whose step 1/1024 is unstable, rkmk4 at 2^16 steps) at its chosen step count (SkipWithError when one
// misses the target), so a smoke run is a correctness check.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/cpu_clock.hpp"
#include "core/group_registry.hpp"
#include "core/integrate.hpp"
#include "core/integrators/methods.hpp"
#include "core/reference_solution.hpp"

namespace {

using namespace lienewton;

// An integrator and the differential of its Newton matrix.
struct Choice {
  Integrator integrator;
  Differential differential = Differential::exact;
  std::string name() const {
    std::string n(to_string(integrator));
    if (differential != Differential::exact) n.append("_").append(to_string(differential));
    return n;
  }
};

struct Race {
  ProblemSpec problem;
  double t_end;
  double target;
  std::vector<Choice> choices;  // the first is the baseline of the ratios
  long reference_steps = 0;     // rkmk4 at this many steps; 0: reference_solution
};

// The integration at `steps` equal steps through the group's own integrate (no request cap on the step count).
IntegrateResult run(const Race& race, Choice choice, long steps) {
  IntegrateRequest req{.problem = race.problem, .h = race.t_end / double(steps), .t_end = race.t_end,
                       .integrator = choice.integrator, .reference = false};
  req.solver.tol = 1e-14;
  req.solver.differential = choice.differential;
  return group_family(race.problem.group).integrate(req, race.problem.start(), {});
}

Eigen::MatrixXd reference_of(const Race& race) {
  return race.reference_steps > 0 ? run(race, {Integrator::rkmk4}, race.reference_steps).y
                                  : reference_solution(race.problem, race.problem.start(), race.t_end).y.value();
}

// The first value reaching the target: from start, farther (next) until the target holds or may_go_on says stop,
// then bisection (middle) between the last value that missed and the first that held while they are apart.
// missed starts at T{} = 0, which apart reads as "no value missed yet" where it must.
template <class T, class ErrorAt, class Next, class MayGoOn, class Apart, class Middle>
T first_reaching(double target, T start, const ErrorAt& error_at, const Next& next, const MayGoOn& may_go_on,
                 const Apart& apart, const Middle& middle, double& error) {
  T missed{}, held = start;
  while (!((error = error_at(held)) <= target) && may_go_on(held)) missed = held, held = next(held);
  while (apart(missed, held)) {
    const T mid = middle(missed, held);
    if (const double e = error_at(mid); e <= target) {
      held = mid;
      error = e;
    } else {
      missed = mid;
    }
  }
  return held;
}

// The fewest steps reaching the target, within 2 %: doubling from 8 steps until the target holds, then bisection
// between the last count that missed it and the first that held.
long steps_for(const Race& race, Choice choice, const Eigen::MatrixXd& y_ref, double& error) {
  return first_reaching(
      race.target, 8L,
      [&](long steps) {
        const IntegrateResult r = run(race, choice, steps);
        return r.status == Status::converged ? (r.y - y_ref).norm() : HUGE_VAL;
      },
      [](long held) { return held * 2; }, [](long held) { return held < 4'000'000; },
      [](long missed, long held) { return held - missed > std::max(1L, held / 50); },
      [](long missed, long held) { return (missed + held) / 2; }, error);
}

void Integrators_Race(benchmark::State& state, const Race& race) {
  const Eigen::MatrixXd y_ref = reference_of(race);
  std::vector<long> steps;
  std::string label;
  for (const Choice& c : race.choices) {
    double error = 0;
    steps.push_back(steps_for(race, c, y_ref, error));
    if (!(error <= race.target)) state.SkipWithError((c.name() + " misses the target").c_str());
    const IntegrateResult r = run(race, c, steps.back());
    if (solves_stages(c.integrator)) state.counters[c.name() + "_iterations_per_step"] = r.mean_iterations;
    label += std::string(label.empty() ? "" : ", ") + c.name() + ": " + std::to_string(steps.back()) + " steps";
  }
  std::vector<double> cpu(race.choices.size(), 0.0);
  for (auto _ : state) {
    for (std::size_t k = 0; k < race.choices.size(); ++k) {
      const double start = thread_cpu_seconds();
      benchmark::DoNotOptimize(run(race, race.choices[k], steps[k]).y.data());
      cpu[k] += thread_cpu_seconds() - start;
    }
  }
  for (std::size_t k = 1; k < race.choices.size(); ++k)
    state.counters[race.choices[0].name() + "_over_" + race.choices[k].name()] = cpu[0] / cpu[k];
  state.SetLabel(label);
}

ProblemSpec stiff_body(double k) {
  ProblemSpec p{.kind = ProblemKind::stiff_body, .group = "SOxR", .n = 3};
  p.stiff_body.k = k;
  return p;
}

// The CPU of one choice at the fewest steps reaching the race's target.
double cpu_for(const Race& race, Choice choice, benchmark::State& state, int repeats) {
  double error = 0;
  const long steps = steps_for(race, choice, reference_of(race), error);
  if (!(error <= race.target)) state.SkipWithError((choice.name() + " misses the target").c_str());
  const double start = thread_cpu_seconds();
  for (int r = 0; r < repeats; ++r) benchmark::DoNotOptimize(run(race, choice, steps).y.data());
  return (thread_cpu_seconds() - start) / repeats;
}

// Stiffness independence (see the file comment): rkmk-radau3 at k = K against k = 1e4, timed in the same run.
void Integrators_Stiffness(benchmark::State& state) {
  const double k = std::pow(10.0, static_cast<double>(state.range(0)));
  const Choice radau{Integrator::rkmk_radau3, Differential::dexpinv_0};
  const Race base{stiff_body(1e4), 1.0, 1e-6, {radau}}, at_k{stiff_body(k), 1.0, 1e-6, {radau}};
  double cpu_base = 0, cpu_k = 0;
  for (auto _ : state) {
    cpu_base += cpu_for(base, radau, state, 5);
    cpu_k += cpu_for(at_k, radau, state, 5);
  }
  state.counters["radau3_cpu_k_over_k1e4"] = cpu_k / cpu_base;
  if (k <= 1e5) {
    const Choice rk4{Integrator::rkmk4};
    state.counters["rkmk4_cpu_k_over_k1e4"] =
        cpu_for({stiff_body(k), 1.0, 1e-6, {rk4}}, rk4, state, 1) /
        cpu_for({stiff_body(1e4), 1.0, 1e-6, {rk4}}, rk4, state, 1);
  }
}

// The integration with adaptive steps at rtol = atol = tol, first step 0.1.
IntegrateResult run_adaptive(const Race& race, Integrator integrator, double tol) {
  IntegrateRequest req{.problem = race.problem, .h = std::min(0.1, race.t_end), .t_end = race.t_end,
                       .integrator = integrator, .reference = false};
  req.rtol = req.atol = tol;
  req.solver.tol = 1e-14;
  return group_family(race.problem.group).integrate(req, race.problem.start(), {});
}

// The largest tolerance whose run reaches the target, within 5 %: dividing by 4 from the target until it holds,
// then bisection in log tol between the last that missed and the first that held.
double tolerance_for(const Race& race, Integrator integrator, const Eigen::MatrixXd& y_ref, double& error) {
  const auto error_at = [&](double tol) {
    const IntegrateResult r = run_adaptive(race, integrator, tol);
    return r.status == Status::converged ? (r.y - y_ref).norm() : HUGE_VAL;
  };
  return first_reaching(
      race.target, race.target, error_at, [](double held) { return held / 4; },
      [](double held) { return held > 1e-14; },
      [](double missed, double held) { return missed > 0 && missed / held > 1.05; },
      [](double missed, double held) { return std::sqrt(missed * held); }, error);
}

std::string text(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

void Integrators_AdaptiveVsFixed(benchmark::State& state, const Race& race) {
  const Integrator integrator = race.choices.front().integrator;
  const Eigen::MatrixXd y_ref = reference_of(race);
  double fixed_error = 0, adaptive_error = 0;
  const long steps = steps_for(race, {integrator}, y_ref, fixed_error);
  const double tol = tolerance_for(race, integrator, y_ref, adaptive_error);
  if (!(fixed_error <= race.target) || !(adaptive_error <= race.target)) state.SkipWithError("misses the target");
  const IntegrateResult adaptive = run_adaptive(race, integrator, tol);
  double fixed_cpu = 0, adaptive_cpu = 0;
  for (auto _ : state) {
    double start = thread_cpu_seconds();
    benchmark::DoNotOptimize(run(race, {integrator}, steps).y.data());
    fixed_cpu += thread_cpu_seconds() - start;
    start = thread_cpu_seconds();
    benchmark::DoNotOptimize(run_adaptive(race, integrator, tol).y.data());
    adaptive_cpu += thread_cpu_seconds() - start;
  }
  state.counters["fixed_over_adaptive"] = fixed_cpu / adaptive_cpu;
  state.SetLabel("fixed: " + std::to_string(steps) + " steps, error " + text(fixed_error) + "; adaptive: tol " +
                 text(tol) + ", " + std::to_string(adaptive.steps.size()) + " steps (" +
                 std::to_string(adaptive.rejected) + " rejected), error " + text(adaptive_error));
}

Race rigid_body_race() {
  return {ProblemSpec{.kind = ProblemKind::rigid_body}, 10.0, 1e-10,
          {{Integrator::dirk_cg2}, {Integrator::rkmk_gauss2}, {Integrator::rkmk_gauss3}}};
}

Race stiff_race() {
  ProblemSpec p;
  p.g = "g = [0 -1 0.5; 1 0 -2; -0.5 2 0] - 10000*skew(y)";
  p.z = Eigen::MatrixXd::Identity(3, 3);
  return {p, 1.0, 1e-6, {{Integrator::rkmk4}, {Integrator::rkmk_radau2}, {Integrator::rkmk_radau3}}, 1L << 16};
}

Race stiff_body_race(double k) {
  return {stiff_body(k), 1.0, 1e-6,
          {{Integrator::rkmk4},
           {Integrator::dirk_cg2},
           {Integrator::rkmk_radau3},
           {Integrator::rkmk_radau3, Differential::dexpinv_0},
           {Integrator::rkmk_radau2},
           {Integrator::rkmk_gauss2}}};
}

BENCHMARK_CAPTURE(Integrators_Race, rigid_body, rigid_body_race())->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(Integrators_Race, stiff, stiff_race())->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(Integrators_Race, stiff_body_k1e4, stiff_body_race(1e4))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(Integrators_Race, stiff_body_k1e5, stiff_body_race(1e5))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK(Integrators_Stiffness)->Arg(5)->Arg(6)->Arg(8)->Unit(benchmark::kMillisecond)->Iterations(1);
Race rigid_body_alone(Integrator integrator) {
  return {ProblemSpec{.kind = ProblemKind::rigid_body}, 10.0, 1e-10, {{integrator}}};
}

Race pulse_alone(Integrator integrator) {
  ProblemSpec p{.n = 3};
  p.g = "s = 1 + 20*exp(-((t - 1)/0.1)^2); w = s * (J \\ (y' * m)); g = [0 -w(3) w(2); w(3) 0 -w(1); -w(2) w(1) 0]";
  p.parameters["J"] = Eigen::Vector3d(1, 2, 3).asDiagonal().toDenseMatrix();
  p.parameters["m"] = Eigen::Vector3d(0.6, 0.8, 0.5);
  return {p, 2.0, 1e-8, {{integrator}}, 1L << 16};
}

BENCHMARK_CAPTURE(Integrators_AdaptiveVsFixed, rigid_body_rkmk4, rigid_body_alone(Integrator::rkmk4))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(20);
BENCHMARK_CAPTURE(Integrators_AdaptiveVsFixed, rigid_body_rkmk_gauss2, rigid_body_alone(Integrator::rkmk_gauss2))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(10);
BENCHMARK_CAPTURE(Integrators_AdaptiveVsFixed, pulse_rkmk4, pulse_alone(Integrator::rkmk4))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(20);

}  // namespace
