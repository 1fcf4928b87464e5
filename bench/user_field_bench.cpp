// A user's g(y) (core/user_field) against the built-in it twins, in one run, timed in thread CPU time (the
// machine is shared) by alternating chunks:
//   UserField_GDg/N        g + dg of paper-sine written as a program vs the built-in PaperSine, on SO(3) (N = 3:
//                          the built-in on fixed-size 3x3 matrices) and SO(8); counters: builtin_ns, user_ns and
//                          ratio = user / built-in (target: within 2)
//   UserField_Sweep/*      the paper's section-5 sweep of paper-sine (3 methods x N = 2..15 x h = 2^-10..2^10,
//                          one thread; "short": N = 3, 8 and h = 1/4, 1, 4) with the program vs the built-in, exact
//                          and finite differences: process CPU seconds and ratio = user / built-in (target: within 2)
//   UserField_Time         g + dg of a non-autonomous program at a fixed t vs the same program with its t-only
//                          part as a parameter: ratio ~1 when the values of t alone are computed once per t
//   UserField_AutoDiff/N   the same g + dg with Eigen's AutoDiffScalar (unsupported/Eigen/AutoDiff) over the
//                          same formula: counters autodiff_ns and ratio = autodiff / the program's evaluator
//   UserField_Compile      parse + compile of a program of about 200 syntax nodes (target: under 1 ms)
// Each checks its own numbers (SkipWithError when the program and the built-in disagree).
#include <benchmark/benchmark.h>

#include <Eigen/Dense>
#include <ctime>
#include <string>
#include <unsupported/Eigen/AutoDiff>
#include <vector>

#include "core/cpu_clock.hpp"
#include "core/groups/so3_group.hpp"
#include "core/groups/son_group.hpp"
#include "core/problems.hpp"
#include "core/sweep.hpp"
#include "core/user_field/program.hpp"
#include "core/user_field/syntax.hpp"
#include "core/user_field/user_vector_field.hpp"

namespace {

using namespace lienewton;
constexpr const char* kSine = "u = sin(y)*(2*y - 5*y^2); g = u - u'";
constexpr int kInputs = 16;
constexpr int kChunk = 32;  // evaluations per timed chunk, alternating built-in and program

template <class G>
struct Inputs {
  std::vector<typename G::Element> y;
  std::vector<typename G::Vector> u;
  Inputs(const G& group, int dim) {
    for (int k = 0; k < kInputs; ++k) {
      y.push_back(group.random(static_cast<std::uint64_t>(k + 1)));
      u.push_back(typename G::Vector(Eigen::VectorXd::LinSpaced(dim, -1.0, 1.0 + 0.1 * k)));
    }
  }
};

template <class G>
double seconds_of(const VectorField<G>& field, const Inputs<G>& in, int& k) {
  const double start = thread_cpu_seconds();
  for (int i = 0; i < kChunk; ++i, k = (k + 1) % kInputs) {
    benchmark::DoNotOptimize(field.g(in.y[static_cast<std::size_t>(k)]));
    benchmark::DoNotOptimize(field.dg(in.y[static_cast<std::size_t>(k)], in.u[static_cast<std::size_t>(k)]));
  }
  return thread_cpu_seconds() - start;
}

template <class G>
void gdg_ratio(benchmark::State& state, const G& group) {
  const auto built_in = make_field(group, ProblemKind::paper_sine, RigidBodyParams{});
  const UserVectorField<G> user(group, user_field::compile(kSine, group.n(), {}));
  const Inputs<G> in(group, group.dim());
  for (int k = 0; k < kInputs; ++k) {
    const auto& y = in.y[static_cast<std::size_t>(k)];
    const auto& u = in.u[static_cast<std::size_t>(k)];
    const double scale = 1.0 + built_in->dg(y, u).norm() + built_in->g(y).norm();
    if ((user.g(y) - built_in->g(y)).norm() + (user.dg(y, u) - built_in->dg(y, u)).norm() > 1e-12 * scale) {
      state.SkipWithError("the program and the built-in disagree");
      return;
    }
  }
  double t_builtin = 0, t_user = 0;
  int kb = 0, ku = 0;
  for (auto _ : state) {
    t_builtin += seconds_of(*built_in, in, kb);
    t_user += seconds_of(user, in, ku);
  }
  const double evals = static_cast<double>(state.iterations()) * kChunk;
  state.counters["builtin_ns"] = 1e9 * t_builtin / evals;
  state.counters["user_ns"] = 1e9 * t_user / evals;
  state.counters["ratio"] = t_user / t_builtin;
}

void UserField_GDg(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  if (n == 3) gdg_ratio(state, SO3Group{});
  else gdg_ratio(state, SONGroup(n));
}
BENCHMARK(UserField_GDg)->Arg(3)->Arg(8);

// paper-sine's g and its derivative along dy by Eigen's AutoDiffScalar: each entry carries its derivative, and
// the products run on the scalar type (no vectorised GEMM).
using Dual = Eigen::AutoDiffScalar<Eigen::Matrix<double, 1, 1>>;
using DualMatrix = Eigen::Matrix<Dual, Eigen::Dynamic, Eigen::Dynamic>;
void autodiff_sine(const Eigen::MatrixXd& y, const Eigen::MatrixXd& dy, Eigen::MatrixXd& g, Eigen::MatrixXd& dg) {
  const Eigen::Index n = y.rows();
  DualMatrix Y(n, n);
  for (Eigen::Index j = 0; j < n; ++j)
    for (Eigen::Index i = 0; i < n; ++i) Y(i, j) = Dual(y(i, j), Eigen::Matrix<double, 1, 1>(dy(i, j)));
  DualMatrix S(n, n);
  for (Eigen::Index k = 0; k < Y.size(); ++k) S(k) = sin(Y(k));
  const DualMatrix U = S * (Dual(2.0) * Y - Dual(5.0) * (Y * Y));
  const DualMatrix G = U - U.transpose();
  g.resize(n, n);
  dg.resize(n, n);
  for (Eigen::Index k = 0; k < G.size(); ++k) {
    g(k) = G(k).value();
    dg(k) = G(k).derivatives()(0);
  }
}

void UserField_AutoDiff(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const SONGroup group(n);
  const auto program = user_field::compile(kSine, n, {});
  // Two points in turn: the evaluator keeps the values of the last y, and each call here is at a new one.
  const Eigen::MatrixXd ys[2] = {group.random(3), group.random(4)};
  const Eigen::MatrixXd u = group.hat(Eigen::VectorXd::LinSpaced(group.dim(), -1.0, 1.0));
  const Eigen::MatrixXd dys[2] = {ys[0] * u, ys[1] * u};
  const Eigen::MatrixXd &y = ys[0], &dy = dys[0];
  Eigen::MatrixXd g1, dg1, g2, dg2;
  program->eval_with_tangent(y, 0.0, dy, g1, dg1);
  autodiff_sine(y, dy, g2, dg2);
  if ((g1 - g2).norm() + (dg1 - dg2).norm() > 1e-12 * (1 + g1.norm() + dg1.norm())) {
    state.SkipWithError("AutoDiff and the program's evaluator disagree");
    return;
  }
  double t_program = 0, t_autodiff = 0;
  for (auto _ : state) {
    double start = thread_cpu_seconds();
    for (int i = 0; i < kChunk; ++i) {
      program->eval_with_tangent(ys[i & 1], 0.0, dys[i & 1], g1, dg1);
      benchmark::DoNotOptimize(dg1.data());
    }
    t_program += thread_cpu_seconds() - start;
    start = thread_cpu_seconds();
    for (int i = 0; i < kChunk; ++i) {
      autodiff_sine(ys[i & 1], dys[i & 1], g2, dg2);
      benchmark::DoNotOptimize(dg2.data());
    }
    t_autodiff += thread_cpu_seconds() - start;
  }
  const double evals = static_cast<double>(state.iterations()) * kChunk;
  state.counters["program_ns"] = 1e9 * t_program / evals;
  state.counters["autodiff_ns"] = 1e9 * t_autodiff / evals;
  state.counters["ratio"] = t_autodiff / t_program;
}
BENCHMARK(UserField_AutoDiff)->Arg(3)->Arg(8)->Arg(32);

// A program of about 200 syntax nodes, as a user might write a longer field.
std::string long_program() {
  std::string s = "A = eye(5) + 0.5 * (y' * y);\n";
  for (int k = 1; k <= 12; ++k) {  // appended: GCC 12 reports a false -Wrestrict on "u" + std::to_string(k)
    const std::string K = std::to_string(k);
    s += 'u';
    s += K;
    s += " = sin(y) * (2*y - ";
    s += K;
    s += "*y^2) + tanh(y(:, 1)) * y(1, :);\n";
  }
  s += "g = skew((u1 + u2 + u3 + u4 + u5 + u6 + u7 + u8 + u9 + u10 + u11 + u12) / A)";
  return s;
}

void UserField_Compile(benchmark::State& state) {
  const std::string source = long_program();
  state.SetLabel("nodes=" + std::to_string(user_field::parse(source).nodes.size()));
  for (auto _ : state) benchmark::DoNotOptimize(user_field::compile(source, 5, {}));
}
BENCHMARK(UserField_Compile)->Unit(benchmark::kMicrosecond);

double process_cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

void UserField_Sweep(benchmark::State& state, Differential differential, bool full) {
  SweepRequest req;
  req.solver.differential = differential;
  req.threads = 1;
  if (!full) {
    req.n = {3, 8};
    req.h = {0.25, 1.0, 4.0};
  }
  SweepRequest built_in = req, user = req;
  built_in.problem.kind = ProblemKind::paper_sine;
  user.problem.g = kSine;
  double t_builtin = 0, t_user = 0;
  int converged_builtin = 0, converged_user = 0;
  double iterations_builtin = 0, iterations_user = 0, twin_builtin = 0, twin_user = 0;
  for (auto _ : state) {
    double start = process_cpu_seconds();
    const SweepResult a = sweep(built_in);
    t_builtin += process_cpu_seconds() - start;
    start = process_cpu_seconds();
    const SweepResult b = sweep(user);
    t_user += process_cpu_seconds() - start;
    if (a.cells.size() != b.cells.size() || a.cells.empty()) state.SkipWithError("the sweeps' grids differ");
    converged_builtin = converged_user = 0;
    for (const auto& c : a.cells) converged_builtin += c.status == Status::converged;
    for (const auto& c : b.cells) converged_user += c.status == Status::converged;
    for (std::size_t i = 0; i < a.cells.size() && i < b.cells.size(); ++i) {
      iterations_builtin += a.cells[i].iterations;
      iterations_user += b.cells[i].iterations;
      if (a.cells[i].iterations == b.cells[i].iterations && a.cells[i].status == b.cells[i].status) {
        twin_builtin += a.cells[i].seconds;
        twin_user += b.cells[i].seconds;
      }
    }
  }
  if (converged_user == 0) state.SkipWithError("no cell converged");
  const double runs = static_cast<double>(state.iterations());
  state.counters["builtin_s"] = t_builtin / runs;
  state.counters["user_s"] = t_user / runs;
  state.counters["ratio"] = t_user / t_builtin;
  state.counters["converged_builtin"] = converged_builtin;
  state.counters["converged_user"] = converged_user;
  state.counters["iterations_builtin"] = iterations_builtin;
  state.counters["iterations_user"] = iterations_user;
  state.counters["twin_ratio"] = twin_user / twin_builtin;
}
BENCHMARK_CAPTURE(UserField_Sweep, exact/short, Differential::exact, false)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(UserField_Sweep, fd/short, Differential::finite_difference, false)
    ->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(UserField_Sweep, exact/full, Differential::exact, true)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(UserField_Sweep, fd/full, Differential::finite_difference, true)
    ->Iterations(1)->Unit(benchmark::kMillisecond);

// A non-autonomous field whose t-only part (a rotation of the skew A by t) is costly: at a fixed t it costs what
// the same program with that part as a parameter costs, since the values of t alone are formed once per t.
void UserField_Time(benchmark::State& state) {
  const int n = 8;
  const SONGroup group(n);
  user_field::Parameters p;
  p["A"] = group.hat(Eigen::VectorXd::LinSpaced(group.dim(), -1.0, 1.0));
  const auto with_t = user_field::compile("B = cos(t) * A + sin(t) * A * A * A; g = skew(sin(y) * B * y)", n, p);
  const double t = 0.3;
  p["B"] = std::cos(t) * p["A"] + std::sin(t) * p["A"] * p["A"] * p["A"];
  const auto with_b = user_field::compile("g = skew(sin(y) * B * y)", n, p);
  const Eigen::MatrixXd ys[2] = {group.random(3), group.random(4)};  // in turn: each call at a new y
  const Eigen::MatrixXd u = group.hat(Eigen::VectorXd::LinSpaced(group.dim(), -1.0, 1.0));
  const Eigen::MatrixXd dys[2] = {ys[0] * u, ys[1] * u};
  const Eigen::MatrixXd &y = ys[0], &dy = dys[0];
  Eigen::MatrixXd g1, dg1, g2, dg2;
  with_t->eval_with_tangent(y, t, dy, g1, dg1);
  with_b->eval_with_tangent(y, t, dy, g2, dg2);
  if ((g1 - g2).norm() + (dg1 - dg2).norm() > 1e-12 * (1 + g1.norm() + dg1.norm())) {
    state.SkipWithError("the program with t and with its t-only part as a parameter disagree");
    return;
  }
  double t_time = 0, t_param = 0;
  for (auto _ : state) {
    double start = thread_cpu_seconds();
    for (int i = 0; i < kChunk; ++i) {
      with_t->eval_with_tangent(ys[i & 1], t, dys[i & 1], g1, dg1);
      benchmark::DoNotOptimize(dg1.data());
    }
    t_time += thread_cpu_seconds() - start;
    start = thread_cpu_seconds();
    for (int i = 0; i < kChunk; ++i) {
      with_b->eval_with_tangent(ys[i & 1], t, dys[i & 1], g2, dg2);
      benchmark::DoNotOptimize(dg2.data());
    }
    t_param += thread_cpu_seconds() - start;
  }
  state.counters["ratio"] = t_time / t_param;
}
BENCHMARK(UserField_Time);

}  // namespace
