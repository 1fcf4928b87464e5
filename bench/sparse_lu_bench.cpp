// The Newton matrix of k bodies (docs/many_bodies.md section 3): I - h J with J block tridiagonal in 12 x 12 blocks
// (12 = SE(3) x R^6's dimension), as the spring chain's implicit Euler step gives. Factor + solve, per call:
//   NewtonMatrix_dense/k   dense PartialPivLU of the (12 k)^2 matrix (what a dense Operator did);
//   NewtonMatrix_sparse/k  SparseLU with its pattern analysed once (as SparseNewtonLu reuses it across a solve);
//   NewtonMatrix_newton/k  detail::NewtonLu, the service's choice (dense up to kDenseLuMaxDim unknowns);
// k = 2 ... 24 for the crossover kDenseLuMaxDim was chosen from, and 32, 128. Each checks its solution's residual.
#include <benchmark/benchmark.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <cmath>
#include <vector>

#include "core/solvers/newton_step.hpp"

namespace {

using namespace lienewton;

constexpr int kBlock = 12;

Eigen::SparseMatrix<double> newton_matrix(int k) {
  std::vector<Eigen::Triplet<double>> entries;
  const int n = kBlock * k;
  for (int i = 0; i < k; ++i)
    for (int j = std::max(0, i - 1); j <= std::min(k - 1, i + 1); ++j)
      for (int r = 0; r < kBlock; ++r)
        for (int c = 0; c < kBlock; ++c) {
          const double x = 0.1 * std::sin(1.3 * (kBlock * i + r) + 0.7 * (kBlock * j + c) + 0.5 * (i - j));
          entries.emplace_back(kBlock * i + r, kBlock * j + c, (i == j && r == c ? 1.0 : 0.0) - x);
        }
  Eigen::SparseMatrix<double> m(n, n);
  m.setFromTriplets(entries.begin(), entries.end());
  m.makeCompressed();
  return m;
}

// Times factor_and_solve(b) on a, then checks the last solution's residual.
template <class FactorAndSolve>
void time_solves(benchmark::State& state, const Eigen::SparseMatrix<double>& a, FactorAndSolve factor_and_solve) {
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(a.rows());
  Eigen::VectorXd x;
  for (auto _ : state) {
    x = factor_and_solve(b);
    benchmark::DoNotOptimize(x.data());
  }
  const double residual = (a * x - b).norm() / b.norm();
  state.counters["residual"] = residual;
  state.counters["unknowns"] = static_cast<double>(a.rows());
  if (!(residual <= 1e-12)) state.SkipWithError("the solution's residual is above 1e-12");
}

void NewtonMatrix_dense(benchmark::State& state) {
  const auto a = newton_matrix(static_cast<int>(state.range(0)));
  const Eigen::MatrixXd dense(a);
  time_solves(state, a, [&](const Eigen::VectorXd& b) -> Eigen::VectorXd {
    return Eigen::PartialPivLU<Eigen::MatrixXd>(dense).solve(b);
  });
}

void NewtonMatrix_sparse(benchmark::State& state) {
  const auto a = newton_matrix(static_cast<int>(state.range(0)));
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.analyzePattern(a);
  time_solves(state, a, [&](const Eigen::VectorXd& b) -> Eigen::VectorXd {
    lu.factorize(a);
    return lu.solve(b);
  });
}

void NewtonMatrix_newton(benchmark::State& state) {
  const auto a = newton_matrix(static_cast<int>(state.range(0)));
  detail::NewtonLu<double> lu;
  time_solves(state, a, [&](const Eigen::VectorXd& b) -> Eigen::VectorXd {
    if (!lu.factorize(a)) state.SkipWithError("singular");
    return lu.solve(b);
  });
}

void sizes(benchmark::internal::Benchmark* b) {
  for (int k : {2, 4, 8, 12, 16, 24, 32, 128}) b->Arg(k);
  b->Unit(benchmark::kMicrosecond);
}
BENCHMARK(NewtonMatrix_dense)->Apply(sizes);
BENCHMARK(NewtonMatrix_sparse)->Apply(sizes);
BENCHMARK(NewtonMatrix_newton)->Apply(sizes);

}  // namespace
