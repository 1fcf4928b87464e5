// The core against the Eigen-generic baseline (eigen_baseline.hpp), in one run:
//   SO3_*           SO(3) closed forms (fixed-size): exp, log, dexpinv (vector and matrix), 3x3 LU solve
//   SON_*/N         SO(N) spectral path, N = 3, 15, 60: exp, log (with domain check), one dexpinv application
//   Eigen_*/N       baseline: MatrixFunctions exp/log, dexpinv by a forward difference of log, dense LU
//   SO3_NewtonIteration  one Newton Version 1 iteration on SO(3), to compare with the sum of its parts
//   Solve_*         a whole SO(3) Newton Version 1 solve (h = 0.5, exact differential) on rigid-body and
//                   paper-linear vs the same algorithm on the baseline with the finite-difference differential
//   Solve_Search/*  paper-sine N = 5: the method alone, through run_method with continuation off, and continued
//   Certify_Segment/q  the branch certificate of one continuation link, on an algebra of dimension q
//   Sweep_*         the paper's default sweep (paper-linear and paper-sine x 3 methods x N = 2..15 x
//                   h = 2^-10..2^10): lienewton with finite-difference and with exact, vs the baseline on a
//                   subset of h (extrapolated, see the label); "/short" is the reduced grid CI runs.
// Every benchmark checks its own numbers (SkipWithError on a wrong result), so a smoke run is a correctness test.
#include <benchmark/benchmark.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "bench/alloc_count.hpp"
#include "bench/eigen_baseline.hpp"
#include "core/solvers/branch_certificate.hpp"
#include "core/solvers/equation.hpp"
#include "core/solvers/run_method.hpp"
#include "core/groups/so3_group.hpp"
#include "core/groups/son_group.hpp"
#include "core/parallel_for.hpp"
#include "core/problems.hpp"
#include "core/solve.hpp"
#include "core/start_point.hpp"
#include "core/sweep.hpp"

namespace {

using namespace lienewton;
constexpr int kInputs = 16;  // inputs cycled through, so nothing is constant-folded or cached

std::vector<Eigen::VectorXd> random_vectors(int dim, double lo, double hi, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> radius(lo, hi);
  std::vector<Eigen::VectorXd> out;
  for (int k = 0; k < kInputs; ++k) {
    Eigen::VectorXd v(dim);
    for (int i = 0; i < dim; ++i) v(i) = normal(rng);
    out.push_back(radius(rng) * v / v.norm());
  }
  return out;
}
std::vector<Eigen::Vector3d> random_vectors3(double lo, double hi, unsigned seed) {
  std::vector<Eigen::Vector3d> out;
  for (const auto& v : random_vectors(3, lo, hi, seed)) out.push_back(v);
  return out;
}

// ---------------------------------------------------------------------------------------------------------
// SO(3) closed forms: the parts of one Newton iteration.

void SO3_Exp(benchmark::State& state) {
  const auto ws = random_vectors3(0.1, 3.0, 1);
  std::size_t i = 0;
  for (auto _ : state) {
    Eigen::Matrix3d r = so3::exp(ws[i++ % kInputs]);
    benchmark::DoNotOptimize(r);
  }
}
BENCHMARK(SO3_Exp);

void SO3_Log(benchmark::State& state) {
  std::vector<Eigen::Matrix3d> rs;
  for (const auto& w : random_vectors3(0.1, 3.0, 2)) rs.push_back(so3::exp(w));
  if ((so3::log(rs[0]) - random_vectors3(0.1, 3.0, 2)[0]).norm() > 1e-13) state.SkipWithError("log(exp w) != w");
  std::size_t i = 0;
  for (auto _ : state) {
    Eigen::Vector3d w = so3::log(rs[i++ % kInputs]);
    benchmark::DoNotOptimize(w);
  }
}
BENCHMARK(SO3_Log);

void SO3_Dexpinv(benchmark::State& state) {  // one application dexpinv_w(u)
  const auto ws = random_vectors3(0.1, 3.0, 3), us = random_vectors3(0.5, 1.5, 4);
  std::size_t i = 0;
  for (auto _ : state) {
    Eigen::Vector3d x = so3::dexpinv(ws[i % kInputs], us[i % kInputs]);
    ++i;
    benchmark::DoNotOptimize(x);
  }
}
BENCHMARK(SO3_Dexpinv);

void SO3_DexpinvMatrix(benchmark::State& state) {  // the 3x3 operator, as a Newton iteration assembles it
  const auto ws = random_vectors3(0.1, 3.0, 5);
  std::size_t i = 0;
  for (auto _ : state) {
    Eigen::Matrix3d d = so3::dexpinv_matrix(ws[i++ % kInputs]);
    benchmark::DoNotOptimize(d);
  }
}
BENCHMARK(SO3_DexpinvMatrix);

void SO3_LUSolve3(benchmark::State& state) {  // fixed-size 3x3 PartialPivLU + solve (the Newton step)
  std::vector<Eigen::Matrix3d> ds;
  const auto ws = random_vectors3(0.1, 3.0, 6), fs = random_vectors3(0.1, 1.0, 7);
  for (const auto& w : ws) ds.push_back(so3::dexpinv_matrix(w) - 0.5 * Eigen::Matrix3d::Identity());
  std::size_t i = 0;
  for (auto _ : state) {
    Eigen::Vector3d u = Eigen::PartialPivLU<Eigen::Matrix3d>(ds[i % kInputs]).solve(fs[i % kInputs]);
    ++i;
    benchmark::DoNotOptimize(u);
  }
}
BENCHMARK(SO3_LUSolve3);

// ---------------------------------------------------------------------------------------------------------
// SO(N) spectral path vs Eigen generic, N = 3, 8, 15, 64.

struct SONInputs {
  explicit SONInputs(int n) : g(n), vs(random_vectors(son::algebra_dim(n), 0.5, 2.5, 10 + n)),
                              us(random_vectors(son::algebra_dim(n), 0.5, 1.5, 20 + n)) {
    for (const auto& v : vs) rs.push_back(g.exp(v));
  }
  SONGroup g;
  std::vector<Eigen::VectorXd> vs, us;
  std::vector<Eigen::MatrixXd> rs;
};

void SON_Exp(benchmark::State& state) {
  const SONInputs in(static_cast<int>(state.range(0)));
  if (in.g.defect(in.rs[0]) > 1e-13) state.SkipWithError("exp not orthogonal");
  std::size_t i = 0;
  for (auto _ : state) {
    Eigen::MatrixXd r = in.g.exp(in.vs[i++ % kInputs]);
    benchmark::DoNotOptimize(r.data());
  }
}
BENCHMARK(SON_Exp)->Arg(3)->Arg(8)->Arg(15)->Arg(64)->Unit(benchmark::kMicrosecond);

void SON_Log(benchmark::State& state) {
  const SONInputs in(static_cast<int>(state.range(0)));
  const Eigen::VectorXd back = in.g.vector(in.g.log(in.rs[0]));
  if ((back - in.vs[0]).norm() > 1e-12 * in.vs[0].norm()) state.SkipWithError("log(exp v) != v");
  std::size_t i = 0;
  for (auto _ : state) {
    Eigen::VectorXd v = in.g.vector(in.g.log(in.rs[i++ % kInputs]));
    benchmark::DoNotOptimize(v.data());
  }
}
BENCHMARK(SON_Log)->Arg(3)->Arg(8)->Arg(15)->Arg(64)->Unit(benchmark::kMicrosecond);

// The log a residual needs (finite differences, fixed point): coordinates and largest angle, no spectral form.
void SON_LogVector(benchmark::State& state) {
  const SONInputs in(static_cast<int>(state.range(0)));
  double angle = 0;
  if ((in.g.log_vector(in.rs[0], angle) - in.vs[0]).norm() > 1e-12 * in.vs[0].norm())
    state.SkipWithError("log_vector(exp v) != v");
  std::size_t i = 0;
  for (auto _ : state) {
    Eigen::VectorXd v = in.g.log_vector(in.rs[i++ % kInputs], angle);
    benchmark::DoNotOptimize(v.data());
  }
}
BENCHMARK(SON_LogVector)->Arg(3)->Arg(8)->Arg(15)->Arg(64)->Unit(benchmark::kMicrosecond);

// One application u -> dexpinv_v(u) given the spectral form of v (which log computed: the solver reuses it).
void SON_Dexpinv(benchmark::State& state) {
  const SONInputs in(static_cast<int>(state.range(0)));
  std::vector<son::SpectralForm> forms;
  for (const auto& r : in.rs) forms.push_back(in.g.log(r));
  std::size_t i = 0;
  for (auto _ : state) {
    Eigen::VectorXd x = in.g.dexpinv(forms[i % kInputs], in.us[i % kInputs]);
    ++i;
    benchmark::DoNotOptimize(x.data());
  }
}
BENCHMARK(SON_Dexpinv)->Arg(3)->Arg(8)->Arg(15)->Arg(64)->Unit(benchmark::kMicrosecond);

void Eigen_Exp(benchmark::State& state) {
  const baseline::EigenGenericGroup g{static_cast<int>(state.range(0))};
  const SONInputs in(g.n);
  if ((g.exp(in.vs[0]) - in.rs[0]).norm() > 1e-12) state.SkipWithError("baseline exp disagrees with lienewton");
  std::size_t i = 0;
  for (auto _ : state) {
    Eigen::MatrixXd r = g.exp(in.vs[i++ % kInputs]);
    benchmark::DoNotOptimize(r.data());
  }
}
BENCHMARK(Eigen_Exp)->Arg(3)->Arg(8)->Arg(15)->Arg(64)->Unit(benchmark::kMicrosecond);

void Eigen_Log(benchmark::State& state) {
  const baseline::EigenGenericGroup g{static_cast<int>(state.range(0))};
  const SONInputs in(g.n);
  if ((g.log(in.rs[0]) - in.vs[0]).norm() > 1e-10 * in.vs[0].norm()) state.SkipWithError("baseline log wrong");
  std::size_t i = 0;
  for (auto _ : state) {
    Eigen::VectorXd v = g.log(in.rs[i++ % kInputs]);
    benchmark::DoNotOptimize(v.data());
  }
}
BENCHMARK(Eigen_Log)->Arg(3)->Arg(8)->Arg(15)->Arg(64)->Unit(benchmark::kMicrosecond);

// What a user without dexpinv writes: (log(exp(v) exp(t u)) - v) / t, one exp and one log per application.
void Eigen_DexpinvFD(benchmark::State& state) {
  const baseline::EigenGenericGroup g{static_cast<int>(state.range(0))};
  const SONInputs in(g.n);
  const Eigen::VectorXd exact = in.g.dexpinv(in.g.spectral(in.vs[0]), in.us[0]);
  if ((g.dexpinv_fd(in.rs[0], in.vs[0], in.us[0]) - exact).norm() > 1e-6 * exact.norm())
    state.SkipWithError("baseline dexpinv disagrees with lienewton beyond FD accuracy");
  std::size_t i = 0;
  for (auto _ : state) {
    Eigen::VectorXd x = g.dexpinv_fd(in.rs[i % kInputs], in.vs[i % kInputs], in.us[i % kInputs]);
    ++i;
    benchmark::DoNotOptimize(x.data());
  }
}
BENCHMARK(Eigen_DexpinvFD)->Arg(3)->Arg(8)->Arg(15)->Arg(64)->Unit(benchmark::kMicrosecond);

// Dense LU solve of the q x q Newton system, dynamic size (the baseline's; q = 3, 105, 1770).
void Eigen_LUSolve(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0)), q = son::algebra_dim(n);
  std::mt19937_64 rng(30);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd d = Eigen::MatrixXd::Identity(q, q);
  Eigen::VectorXd f(q);
  for (int i = 0; i < q; ++i) {
    f(i) = normal(rng);
    for (int j = 0; j < q; ++j) d(i, j) += 0.3 * normal(rng) / std::sqrt(double(q));
  }
  for (auto _ : state) {
    Eigen::VectorXd u = baseline::lu_solve(d, f);
    benchmark::DoNotOptimize(u.data());
  }
  state.SetLabel("q = " + std::to_string(q));
}
BENCHMARK(Eigen_LUSolve)->Arg(3)->Arg(8)->Arg(15)->Arg(64)->Unit(benchmark::kMicrosecond);

// ---------------------------------------------------------------------------------------------------------
// A whole SO(3) Newton Version 1 solve, h = 0.5, from the paper's start point (seed 1).

const char* problem_name(ProblemKind k) { return k == ProblemKind::rigid_body ? "rigid_body" : "paper_linear"; }

void Solve_Lienewton(benchmark::State& state, ProblemKind problem) {
  SolveRequest req;
  req.problem.kind = problem;
  req.problem.n = 3;
  req.h = 0.5;
  req.solver.method = Method::newton_group;
  req.solver.differential = Differential::exact;
  req.problem.z = start_point(3, 1);
  const SolveResult check = solve(req);
  if (check.status != Status::converged) state.SkipWithError("lienewton SO(3) solve did not converge");
  // Heap allocations of a whole solve() call (request copy, field, result and trace: outside the iterations).
  const long allocations = bench::allocations_in([&] { benchmark::DoNotOptimize(solve(req).residual); });
  for (auto _ : state) {
    SolveResult r = solve(req);
    benchmark::DoNotOptimize(r.residual);
  }
  state.counters["iterations"] = check.iterations;
  state.counters["residual"] = check.residual;
  state.counters["heap_allocations_per_solve"] = static_cast<double>(allocations);
  state.SetLabel(std::string(problem_name(problem)) + ", newton-group, exact, h = 0.5");
}
BENCHMARK_CAPTURE(Solve_Lienewton, rigid_body, ProblemKind::rigid_body)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(Solve_Lienewton, paper_linear, ProblemKind::paper_linear)->Unit(benchmark::kMicrosecond);

// The same solve through the solver template directly (no request validation / result packaging), and with
// lienewton's finite-difference differential: isolates what the exact closed forms buy.
void Solve_LienewtonFD(benchmark::State& state, ProblemKind problem) {
  SolveRequest req;
  req.problem.kind = problem;
  req.problem.n = 3;
  req.h = 0.5;
  req.solver.method = Method::newton_group;
  req.solver.differential = Differential::finite_difference;
  req.problem.z = start_point(3, 1);
  const SolveResult check = solve(req);
  if (check.status != Status::converged) state.SkipWithError("lienewton SO(3) FD solve did not converge");
  for (auto _ : state) {
    SolveResult r = solve(req);
    benchmark::DoNotOptimize(r.residual);
  }
  state.counters["iterations"] = check.iterations;
  state.SetLabel(std::string(problem_name(problem)) + ", newton-group, finite-difference, h = 0.5");
}
BENCHMARK_CAPTURE(Solve_LienewtonFD, rigid_body, ProblemKind::rigid_body)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(Solve_LienewtonFD, paper_linear, ProblemKind::paper_linear)->Unit(benchmark::kMicrosecond);

// What continuation costs, and that it costs nothing when off: the same solve (paper-sine, N = 5, h = 1/4, Version 1,
// exact) by the method alone (run_directly), through run_method with continuation off (must be the same time:
// the ratio of the two in one run is the overhead of the searches' switch), and continued along z's branch.
enum class Search { direct, off, continued };
void Solve_Search(benchmark::State& state, Search search) {
  const SONGroup group(5);
  const auto field = make_field(group, ProblemKind::paper_sine, RigidBodyParams{});
  const auto eq = Equation<SONGroup>::implicit_euler(group, start_point(5, 1), 0.25, *field);
  SolverOptions opt;
  opt.continuation = search == Search::continued;
  const auto run = [&] {
    return search == Search::direct ? run_directly(Method::newton_group, eq, opt, {})
                                    : run_method(Method::newton_group, eq, opt, {});
  };
  const SolveResult check = run();
  if (check.status != Status::converged) state.SkipWithError("paper-sine N = 5, h = 1/4 did not converge");
  for (auto _ : state) benchmark::DoNotOptimize(run().residual);
  state.counters["iterations"] = check.total_iterations();
  state.counters["path_points"] = static_cast<double>(check.continuation.size());
  state.SetLabel(search == Search::direct ? "method alone" : search == Search::off ? "continuation off" : "continued");
}
BENCHMARK_CAPTURE(Solve_Search, direct, Search::direct)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(Solve_Search, continuation_off, Search::off)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(Solve_Search, continued, Search::continued)->Unit(benchmark::kMicrosecond);

// The branch certificate of one path link (branch_certificate.hpp) alone, on an algebra of dimension q (3: SO(3),
// 10: SO(5), 120: SO(16)): its cost beside Solve_Search's whole continued solve on SO(5) in the same run.
void Certify_Segment(benchmark::State& state) {
  const int q = static_cast<int>(state.range(0));
  const auto v = random_vectors(q, 0.1, 0.3, 7);
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(q, q);
  const auto jacobian = [&] { return Eigen::MatrixXd(identity - 0.05 / std::sqrt(q) * Eigen::MatrixXd::Random(q, q)); };
  BranchLink link{.x_a = v[0], .x_b = v[1], .tau_a = 0.0, .tau_b = 0.25, .d_a = jacobian(), .d_b = jacobian(),
                  .d_mid = {}, .f_mid = {}};
  for (std::size_t k = 0; k < 3; ++k) {
    link.d_mid[k] = jacobian();
    link.f_mid[k] = 1e-3 * v[k + 2];
  }
  if (!certify_link(link).holds) state.SkipWithError("a link this near the identity must be certified");
  for (auto _ : state) benchmark::DoNotOptimize(certify_link(link).contraction);
}
BENCHMARK(Certify_Segment)->Arg(3)->Arg(10)->Arg(120)->Unit(benchmark::kMicrosecond);

// One Newton Version 1 iteration on SO(3) (exact differential), exactly as newton_group runs it: evaluate f
// at y_n with the spectral form, assemble the 3x3 differential, LU-solve, y_{n+1} = y_n exp(u). Cycled over
// the iterates of the rigid-body solve above. Compare with SO3_Exp + SO3_Log + SO3_DexpinvMatrix + SO3_LUSolve3.
void SO3_NewtonIteration(benchmark::State& state) {
  SolveRequest req;
  req.problem.kind = ProblemKind::rigid_body;
  req.problem.n = 3;
  req.h = 0.5;
  req.problem.z = start_point(3, 1);
  req.solver.include_iterates = true;
  const SolveResult solved = solve(req);
  const SO3Group group;
  const auto field = make_field(group, req.problem.kind, req.problem.rigid_body);
  const auto eq = Equation<SO3Group>::implicit_euler(group, Eigen::Matrix3d(*req.problem.z), req.h, *field);
  std::vector<Eigen::Matrix3d> ys;
  for (const auto& t : solved.trace) {
    if (t.iteration < solved.iterations) ys.push_back(t.y);
  }
  if (ys.empty()) {
    state.SkipWithError("no iterates");
    return;
  }
  // The first iteration must reproduce the solver's y_1.
  {
    const auto p = eq.at(ys[0], Equation<SO3Group>::Need::differential);
    const Eigen::Vector3d u = -Eigen::PartialPivLU<Eigen::Matrix3d>(eq.df_matrix(p, Differential::exact)).solve(p.f);
    if (ys.size() > 1 && (group.times_exp(ys[0], u) - ys[1]).norm() > 1e-14) state.SkipWithError("iteration != solver's");
  }
  auto iteration = [&](const Eigen::Matrix3d& y) {
    const auto p = eq.at(y, Equation<SO3Group>::Need::differential);
    const Eigen::Matrix3d d = eq.df_matrix(p, Differential::exact);
    const Eigen::Vector3d u = -Eigen::PartialPivLU<Eigen::Matrix3d>(d).solve(p.f);
    Eigen::Matrix3d next = group.times_exp(p.y, u);
    benchmark::DoNotOptimize(next);
  };
  long allocations = 0;
  for (const auto& y : ys) allocations += bench::allocations_in([&] { iteration(y); });
  if (allocations != 0) state.SkipWithError("an SO(3) iteration allocated on the heap");
  std::size_t i = 0;
  for (auto _ : state) iteration(ys[i++ % ys.size()]);
  state.counters["iterates"] = static_cast<double>(ys.size());
  state.counters["heap_allocations"] = static_cast<double>(allocations);
  state.SetLabel("rigid-body, h = 0.5, exact: f(y) + 3x3 differential + LU + y exp(u)");
}
BENCHMARK(SO3_NewtonIteration);

void Solve_Baseline(benchmark::State& state, ProblemKind problem) {
  baseline::Problem p;
  p.kind = problem;
  p.z = start_point(3, 1);
  p.h = 0.5;
  SolveRequest req;
  req.problem.kind = problem;
  req.problem.n = 3;
  req.h = 0.5;
  req.problem.z = p.z;
  const SolveResult ours = solve(req);
  const baseline::Result check = baseline::newton_group(p);
  if (!check.converged) state.SkipWithError("baseline SO(3) solve did not converge");
  else if ((check.y - ours.y).norm() > 1e-12) state.SkipWithError("baseline and lienewton solutions differ");
  for (auto _ : state) {
    baseline::Result r = baseline::newton_group(p);
    benchmark::DoNotOptimize(r.residual);
  }
  state.counters["iterations"] = check.iterations;
  state.counters["residual"] = check.residual;
  state.SetLabel(std::string(problem_name(problem)) + ", Eigen MatrixFunctions + forward differences + dense LU");
}
BENCHMARK_CAPTURE(Solve_Baseline, rigid_body, ProblemKind::rigid_body)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(Solve_Baseline, paper_linear, ProblemKind::paper_linear)->Unit(benchmark::kMicrosecond);

// ---------------------------------------------------------------------------------------------------------
// The paper's default sweep. Grids: full = N 2..15 x h 2^-10..2^10 (21); short = N 2..4 x h 2^{-10,-5,0,5,10};
// subset = N 2..15 x h 2^{-10,-5,0,5,10} (5 of 21 h values: the baseline's grid, extrapolated x 21/5).

struct Grid {
  std::vector<int> n;
  std::vector<double> h;
};
Grid grid(const std::string& which) {
  Grid g;
  const int n_max = which == "short" ? 4 : 15;
  for (int n = 2; n <= n_max; ++n) g.n.push_back(n);
  if (which == "full") {
    for (int e = -10; e <= 10; ++e) g.h.push_back(std::ldexp(1.0, e));
  } else {
    for (int e = -10; e <= 10; e += 5) g.h.push_back(std::ldexp(1.0, e));
  }
  return g;
}
constexpr ProblemKind kSweepProblems[] = {ProblemKind::paper_linear, ProblemKind::paper_sine};

void Sweep_Lienewton(benchmark::State& state, Differential differential, std::string which) {
  const Grid g = grid(which);
  int cells = 0, converged = 0;
  for (auto _ : state) {
    cells = converged = 0;
    for (ProblemKind problem : kSweepProblems) {
      SweepRequest req;
      req.problem.kind = problem;
      req.solver.differential = differential;
      req.n = g.n;
      req.h = g.h;
      const SweepResult res = sweep(req);
      for (const auto& c : res.cells) converged += c.status == Status::converged;
      cells += static_cast<int>(res.cells.size());
    }
  }
  const int expected = 2 * 3 * static_cast<int>(g.n.size() * g.h.size());
  if (cells != expected) state.SkipWithError("sweep returned the wrong number of cells");
  if (converged == 0) state.SkipWithError("no cell converged");
  state.counters["cells"] = cells;
  state.counters["converged"] = converged;
  state.counters["threads"] = resolve_thread_count(0);
  state.SetLabel(which + " grid, " + (differential == Differential::exact ? "exact" : "finite-difference") +
                 ", paper-linear + paper-sine, all cores");
}
BENCHMARK_CAPTURE(Sweep_Lienewton, fd/short, Differential::finite_difference, std::string("short"))
    ->Iterations(1)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Sweep_Lienewton, exact/short, Differential::exact, std::string("short"))
    ->Iterations(1)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Sweep_Lienewton, fd/subset, Differential::finite_difference, std::string("subset"))
    ->Iterations(1)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Sweep_Lienewton, exact/subset, Differential::exact, std::string("subset"))
    ->Iterations(1)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Sweep_Lienewton, fd/full, Differential::finite_difference, std::string("full"))
    ->Iterations(1)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Sweep_Lienewton, exact/full, Differential::exact, std::string("full"))
    ->Iterations(1)->UseRealTime()->Unit(benchmark::kMillisecond);

// The baseline sweep, on both cores too (cells claimed from a shared counter, as lienewton's sweep does).
void Sweep_Baseline(benchmark::State& state, std::string which) {
  const Grid g = grid(which);
  std::vector<Eigen::MatrixXd> z;
  for (int n : g.n) z.push_back(start_point(n, 1));
  const int per_problem = 3 * static_cast<int>(g.n.size() * g.h.size());
  std::vector<char> converged(2 * per_problem, 0);
  for (auto _ : state) {
    parallel_for(2 * per_problem, 0, [&](int index) {
      const int pi = index / per_problem, rest = index % per_problem;
      const int m = rest / static_cast<int>(g.n.size() * g.h.size());
      const int ni = (rest / static_cast<int>(g.h.size())) % static_cast<int>(g.n.size());
      const int hi = rest % static_cast<int>(g.h.size());
      baseline::Problem p;
      p.kind = kSweepProblems[pi];
      p.z = z[ni];
      p.h = g.h[hi];
      converged[index] = baseline::run(kAllMethods[m], p).converged;
      return true;
    });
  }
  int total = 0;
  for (char c : converged) total += c;
  if (total == 0) state.SkipWithError("no baseline cell converged");
  const double factor = which == "full" ? 1.0 : 21.0 / static_cast<double>(g.h.size());
  state.counters["cells"] = 2 * per_problem;
  state.counters["converged"] = total;
  state.counters["extrapolation_factor"] = factor;
  state.counters["threads"] = resolve_thread_count(0);
  state.SetLabel(which + " grid (" + std::to_string(g.h.size()) + " of 21 h values" +
                 (which == "subset" ? "; full default sweep ~ time x 21/5, compare with Sweep_Lienewton/*/subset" : "") +
                 "), Eigen MatrixFunctions + forward differences + dense LU, all cores");
}
BENCHMARK_CAPTURE(Sweep_Baseline, short, std::string("short"))
    ->Iterations(1)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(Sweep_Baseline, subset, std::string("subset"))
    ->Iterations(1)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace
