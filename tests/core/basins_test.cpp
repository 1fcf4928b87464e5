// Basin maps: classification against known roots, the roots' truth checked by an
// independent oracle, the same map for any thread count, caps, cancellation, and y0 on a solve.
#include <gtest/gtest.h>

#include <map>

#include "core/basin_map.hpp"
#include "core/basins.hpp"
#include "core/cancellation.hpp"
#include "core/groups/so3_group.hpp"
#include "core/request_error.hpp"
#include "core/solve.hpp"
#include "core/start_point.hpp"
#include "residual_oracle.hpp"
#include "reversed_farm.hpp"

namespace lienewton {
namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;

// f(y) = vee(D y - (D y)^T) / 2 on SO(3), D = diag(1, 2, 3): its zeros are the critical points of tr(D y),
// where D y is symmetric: the four diagonal sign matrices of SO(3), known exactly.
const Matrix3d kD = Vector3d(1, 2, 3).asDiagonal();
Vector3d trace_gradient(const Matrix3d& y) { return so3::vee(kD * y - (kD * y).transpose()) / 2; }
// df_y(u) = d/dt f(y exp(t u)) = vee(D y u^ + u^ y^T D) / 2 (3.4).
Vector3d trace_gradient_df(const Matrix3d& y, const Vector3d& u) {
  const Matrix3d du = kD * y * so3::hat(u);
  return so3::vee(du - du.transpose()) / 2;
}
std::vector<Matrix3d> known_roots() {
  return {Vector3d(1, 1, 1).asDiagonal(), Vector3d(1, -1, -1).asDiagonal(), Vector3d(-1, 1, -1).asDiagonal(),
          Vector3d(-1, -1, 1).asDiagonal()};
}

BasinPlane plane(int size, std::vector<Method> methods, int threads = 0) {
  BasinPlane p;
  p.b1 = Eigen::VectorXd::Unit(3, 0);
  p.b2 = Eigen::VectorXd::Unit(3, 1);
  p.size = size;
  p.methods = std::move(methods);
  p.threads = threads;
  return p;
}

TEST(BasinMap, ClassifiesEveryPixelByTheKnownRootItReached) {
  const auto eq = Equation<SO3Group>::general(SO3Group{}, Matrix3d::Identity(), trace_gradient, trace_gradient_df);
  const BasinPlane p = plane(17, {Method::newton_group, Method::newton_algebra});
  const BasinResult map = basin_map(eq, p);
  ASSERT_TRUE(map.complete);
  ASSERT_EQ(map.rows.size(), 17u);
  // Every root is one of the four, and no two roots are the same one.
  std::map<int, int> known_of_root;
  const auto known = known_roots();
  for (const BasinRoot& root : map.roots) {
    int match = -1;
    for (std::size_t k = 0; k < known.size(); ++k)
      if ((root.y - known[k]).norm() < 1e-12) match = static_cast<int>(k);
    ASSERT_GE(match, 0) << "root " << root.id << " is no critical point of tr(D y):\n" << root.y;
    for (const auto& [other, k] : known_of_root) EXPECT_NE(k, match) << "roots " << other << " and " << root.id;
    known_of_root[root.id] = match;
  }
  // Starts in the x-y plane through I reach all four (the identity, and the half turns about x, y, z).
  EXPECT_EQ(map.roots.size(), 4u);
  // Each pixel's label is what a solve from its start returns: re-solve every 5th pixel independently.
  int checked = 0;
  for (const BasinRow& row : map.rows) {
    for (int column = 0; column < p.size; column += 5) {
      for (std::size_t m = 0; m < p.methods.size(); ++m) {
        auto start = eq;
        start.start_at(SO3Group{}.times_exp(Matrix3d::Identity(),
                                            Vector3d(map.grid.axis[static_cast<std::size_t>(column)], row.b, 0)));
        const SolveResult r = run_method(p.methods[m], start, SolverOptions{}, {});
        const BasinPixel& pixel = row.pixels[m][static_cast<std::size_t>(column)];
        ASSERT_EQ(pixel.status, r.status);
        ASSERT_EQ(pixel.iterations, r.iterations);
        if (r.status != Status::converged) {
          EXPECT_EQ(pixel.root, -1);
          continue;
        }
        ASSERT_GE(pixel.root, 0);
        EXPECT_LT((r.y - map.roots[static_cast<std::size_t>(pixel.root)].y).norm(), 1e-10);
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 50);
  // The summary counts what the rows hold.
  for (std::size_t m = 0; m < p.methods.size(); ++m) {
    const BasinMethodSummary& s = map.methods[m];
    EXPECT_EQ(s.pixels, 17 * 17);
    int converged = 0;
    std::set<int> reached;
    for (const BasinRow& row : map.rows)
      for (const BasinPixel& px : row.pixels[m])
        if (px.status == Status::converged) ++converged, reached.insert(px.root);
    EXPECT_EQ(s.converged, converged);
    EXPECT_EQ(s.basins, static_cast<int>(reached.size()));
    EXPECT_DOUBLE_EQ(s.converged_fraction, converged / 289.0);
  }
}

TEST(BasinMap, RootsAreNumberedInPixelOrder) {
  const auto eq = Equation<SO3Group>::general(SO3Group{}, Matrix3d::Identity(), trace_gradient, trace_gradient_df);
  const BasinResult map = basin_map(eq, plane(15, {Method::newton_group}));
  int next = 0;
  for (const BasinRow& row : map.rows) {
    for (const BasinPixel& px : row.pixels[0]) {
      if (px.root < 0) continue;
      ASSERT_LE(px.root, next);  // a new id is always the next one
      if (px.root == next) ++next;
    }
  }
  EXPECT_EQ(next, static_cast<int>(map.roots.size()));
}

// The independent truth for paper-linear: g from the paper, the defect of (1.1) with Eigen's Pade exp.
MatrixXd paper_linear_g(const MatrixXd& y) {
  MatrixXd g = MatrixXd::Zero(y.rows(), y.cols());
  for (Eigen::Index i = 0; i + 1 < y.rows(); ++i) {
    g(i, i + 1) = y(i, i + 1);
    g(i + 1, i) = -y(i, i + 1);
  }
  return g;
}

BasinRequest paper_linear_request(double h, int size, int threads) {
  BasinRequest r;
  r.solve.problem.kind = ProblemKind::paper_linear;
  r.solve.problem.n = 3;
  r.solve.h = h;
  r.solve.solver.differential = Differential::exact;
  r.size = size;
  r.threads = threads;
  return r;
}

TEST(Basins, EveryRootSolvesTheEquationAndRootsAreDistinct) {
  const BasinRequest req = paper_linear_request(4.0, 24, 0);
  const BasinResult map = basins(req);
  const MatrixXd z = start_point(3, req.solve.problem.seed);
  ASSERT_GE(map.roots.size(), 2u);  // h = 4 has several roots within reach
  for (const BasinRoot& root : map.roots) {
    const MatrixXd w = req.solve.h * paper_linear_g(root.y);
    EXPECT_LT((root.y - z * oracle_exp(w)).norm(), 1e-12) << "root " << root.id;
    EXPECT_LE(root.residual, req.solve.solver.tol);
    EXPECT_NEAR(root.distance_from_z, oracle_log(z.transpose() * root.y).norm() / std::sqrt(2.0), 1e-10);
    for (const BasinRoot& other : map.roots) {
      if (other.id >= root.id) break;
      EXPECT_GT(oracle_log(z.transpose() * root.y).norm(), 0);
      EXPECT_GT(oracle_log(other.y.transpose() * root.y).norm() / std::sqrt(2.0), kRootDistance);
    }
  }
}

// Two maps are the same pixel for pixel (status, root id, iterations), row for row (new roots) and root for root
// (y bit for bit).
void expect_same_map(const BasinResult& expected, const BasinResult& actual) {
  ASSERT_EQ(actual.rows.size(), expected.rows.size());
  for (std::size_t i = 0; i < expected.rows.size(); ++i) {
    EXPECT_EQ(actual.rows[i].row, static_cast<int>(i));
    EXPECT_EQ(actual.rows[i].new_roots, expected.rows[i].new_roots);
    ASSERT_EQ(actual.rows[i].pixels.size(), expected.rows[i].pixels.size());
    for (std::size_t m = 0; m < expected.rows[i].pixels.size(); ++m)
      for (std::size_t c = 0; c < expected.rows[i].pixels[m].size(); ++c) {
        const BasinPixel &a = expected.rows[i].pixels[m][c], &b = actual.rows[i].pixels[m][c];
        ASSERT_EQ(a.status, b.status) << "row " << i << " column " << c << " method " << m;
        ASSERT_EQ(a.root, b.root) << "row " << i << " column " << c << " method " << m;
        ASSERT_EQ(a.iterations, b.iterations) << "row " << i << " column " << c << " method " << m;
      }
  }
  ASSERT_EQ(actual.roots.size(), expected.roots.size());
  for (std::size_t k = 0; k < expected.roots.size(); ++k) {
    EXPECT_EQ(actual.roots[k].id, static_cast<int>(k));
    EXPECT_EQ(actual.roots[k].y, expected.roots[k].y);  // bitwise
    EXPECT_EQ(actual.roots[k].residual, expected.roots[k].residual);
  }
}

TEST(Basins, SameMapForOneAndTwoThreads) {
  expect_same_map(basins(paper_linear_request(4.0, 20, 1)), basins(paper_linear_request(4.0, 20, 2)));
}

// The farm path (MPI ranks in the CLI): rows computed last-first and passed as bytes give the threads' map, roots
// numbered in pixel order and their y bit for bit; a process that only computes for the farm returns no rows.
TEST(Basins, FarmGivesTheSameMapAsThreads) {
  const BasinRequest req = paper_linear_request(4.0, 20, 2);
  const BasinResult threads = basins(req);
  const ReversedFarm farm;
  const BasinResult farmed = basins(req, {}, &farm);
  ASSERT_TRUE(farmed.complete);
  ASSERT_GE(threads.roots.size(), 2u);
  expect_same_map(threads, farmed);
  const ReversedFarm worker(true);
  EXPECT_TRUE(basins(req, {}, &worker).rows.empty());
}

// Shards: three parts, each holding every third row with its own root numbering, merged in shuffled
// order give the unsharded map: pixels, renumbered roots, new roots per row, summaries. A part holds exactly its
// rows; a missing, repeated or foreign part is refused naming `shard`.
TEST(Basins, ShardsMergeToTheUnshardedMap) {
  const BasinRequest req = paper_linear_request(4.0, 21, 2);
  const BasinResult whole = basins(req);
  ASSERT_GE(whole.roots.size(), 2u);  // two roots, and at this size two parts meet the second one first
  std::vector<BasinResult> parts;
  for (int index : {2, 0, 1}) {
    BasinRequest part = req;
    part.shard = Shard{index, 3};
    parts.push_back(basins(part));
    ASSERT_TRUE(parts.back().complete);
    ASSERT_EQ(parts.back().rows.size(), 7u);
    for (std::size_t k = 0; k < 7; ++k) EXPECT_EQ(parts.back().rows[k].row, index + 3 * static_cast<int>(k));
  }
  // Some part meets the roots in another order than the whole map: the merge has to renumber.
  EXPECT_TRUE(std::any_of(parts.begin(), parts.end(), [&](const BasinResult& part) {
    return !part.roots.empty() && (part.roots[0].y - whole.roots[0].y).norm() > 1e-3;
  }));
  const BasinResult merged = merge_shards(parts);
  EXPECT_TRUE(merged.complete);
  EXPECT_FALSE(merged.shard);
  expect_same_map(whole, merged);
  ASSERT_EQ(merged.methods.size(), whole.methods.size());
  for (std::size_t m = 0; m < whole.methods.size(); ++m) {
    EXPECT_EQ(merged.methods[m].method, whole.methods[m].method);
    EXPECT_EQ(merged.methods[m].converged, whole.methods[m].converged);
    EXPECT_EQ(merged.methods[m].basins, whole.methods[m].basins);
    EXPECT_EQ(merged.methods[m].mean_iterations, whole.methods[m].mean_iterations);  // same summation order
    EXPECT_EQ(merged.methods[m].status_counts, whole.methods[m].status_counts);
  }
  EXPECT_EQ(merged.seconds, parts[0].seconds + parts[1].seconds + parts[2].seconds);

  const auto refusal = [](const std::vector<BasinResult>& p) {
    try {
      merge_shards(p);
    } catch (const RequestError& e) {
      return e.field();
    }
    return std::string("merged");
  };
  EXPECT_EQ(refusal({parts[0], parts[1]}), "shard");            // missing
  EXPECT_EQ(refusal({parts[0], parts[1], parts[1]}), "shard");  // repeated
  EXPECT_EQ(refusal({whole}), "shard");                         // unsharded
  BasinRequest other = req;
  other.solve.h = 0.5;
  other.shard = Shard{0, 3};
  other.request_key = "h = 0.5";
  EXPECT_EQ(refusal({parts[0], basins(other), parts[2]}), "shard");  // foreign: another request
  other.request_key.clear();
  other.solve.problem.seed = 7;
  EXPECT_EQ(refusal({parts[0], basins(other), parts[2]}), "shard");  // foreign: another z
}

TEST(Basins, StopsWhenTheCallbackSaysSoOrTheTokenIsCancelled) {
  int rows = 0;
  const BasinResult stopped = basins(paper_linear_request(0.5, 16, 2), [&](const BasinRow&, const auto&) {
    return ++rows < 3;
  });
  EXPECT_EQ(rows, 3);
  EXPECT_EQ(stopped.rows.size(), 3u);
  EXPECT_FALSE(stopped.complete);

  const CancellationToken past(CancellationToken::Clock::now(), nullptr, nullptr);
  const CancellationScope scope(&past);
  const BasinResult cancelled = basins(paper_linear_request(0.5, 16, 2));
  EXPECT_TRUE(cancelled.rows.empty());
  EXPECT_FALSE(cancelled.complete);
}

std::string field_of(const BasinRequest& req) {
  try {
    validate(req);
  } catch (const RequestError& e) {
    return e.field() + (e.kind() == RequestError::Kind::unprocessable ? " 422" : " 400");
  }
  return "valid";
}

TEST(Basins, ValidationNamesTheField) {
  BasinRequest r = paper_linear_request(0.5, 16, 0);
  EXPECT_EQ(field_of(r), "valid");
  r.size = kMaxBasinSize + 1;
  EXPECT_EQ(field_of(r), "size 422");
  r.size = 0;
  EXPECT_EQ(field_of(r), "size 400");
  r = paper_linear_request(0.5, 16, 0);
  r.radius = std::nan("");
  EXPECT_EQ(field_of(r), "r 400");
  r.radius = -1;
  EXPECT_EQ(field_of(r), "r 400");
  r = paper_linear_request(0.5, 16, 0);
  r.b1 = Eigen::VectorXd::Ones(4);
  EXPECT_EQ(field_of(r), "b1 422");
  r.b1 = Eigen::Vector3d(1, 2, 0);
  r.b2 = Eigen::Vector3d(-2, -4, 0);
  EXPECT_EQ(field_of(r), "b2 422");
  r.b2 = Eigen::Vector3d(0, 0, std::numeric_limits<double>::infinity());
  EXPECT_EQ(field_of(r), "b2 400");
  r = paper_linear_request(0.5, 16, 0);
  r.solve.problem.n = 2;
  EXPECT_EQ(field_of(r), "n 422");
  r = paper_linear_request(0.5, 16, 0);
  r.methods = {Method::newton_group, Method::newton_group};
  EXPECT_EQ(field_of(r), "methods 400");
  r = paper_linear_request(0.5, 16, 0);
  r.shard = Shard{3, 3};
  EXPECT_EQ(field_of(r), "shard.index 422");
}

TEST(Basins, AxisIsPixelCentres) {
  const std::vector<double> axis = basin_axis(4, 2.0);
  EXPECT_EQ(axis, (std::vector<double>{-1.5, -0.5, 0.5, 1.5}));
}

// y0 on a solve: the start moves, z (the equation) stays.
TEST(SolveStart, Y0MovesTheStartNotTheEquation) {
  SolveRequest base;
  base.problem.n = 3;
  base.h = 4.0;
  base.solver.differential = Differential::exact;
  const MatrixXd z = start_point(3, base.problem.seed);
  // y0 = z itself: the paper's start, the same solve bit for bit.
  SolveRequest at_z = base;
  at_z.y0 = z;
  EXPECT_EQ(solve(base).y, solve(at_z).y);
  // A basin pixel's start reproduces its classification.
  const BasinRequest req = paper_linear_request(4.0, 9, 1);
  const BasinResult map = basins(req);
  for (std::size_t m = 0; m < req.methods.size(); ++m) {
    SolveRequest moved = base;
    moved.solver.method = req.methods[m];
    // The pixel's own start, formed as the map forms it (z exp(w) as z + z expm1(w)): at h = 4 the basins are
    // fractal, and a start one rounding away may end elsewhere.
    moved.y0 = MatrixXd(SO3Group{}.times_exp(Matrix3d(z), Vector3d(map.grid.axis[1], map.grid.axis[7], 0)));
    const SolveResult r = solve(moved);
    const BasinPixel& px = map.rows[7].pixels[m][1];
    EXPECT_EQ(r.status, px.status);
    EXPECT_EQ(r.iterations, px.iterations);
    if (px.root >= 0) {
      EXPECT_LT((r.y - map.roots[static_cast<std::size_t>(px.root)].y).norm(), 1e-10);
    }
  }
}

// The globalised Newton starts at y0 too: its first record is f(y0), by an independent oracle, for both
// versions and both strategies (a start far from z: the residual at z differs by more than 0.1).
TEST(SolveStart, GlobalizedNewtonStartsAtY0) {
  SolveRequest r;
  r.problem.n = 3;
  r.h = 4.0;
  const MatrixXd z = start_point(3, r.problem.seed);
  const MatrixXd y0 = MatrixXd(SO3Group{}.times_exp(Matrix3d(z), Vector3d(1.2, -0.7, 0.4)));
  r.y0 = y0;
  const double at_y0 = oracle(ProblemKind::paper_linear, r.h, z, y0).residual;
  ASSERT_GT(std::abs(at_y0 - oracle(ProblemKind::paper_linear, r.h, z, z).residual), 0.1);
  for (Method m : {Method::newton_group, Method::newton_algebra}) {
    for (Globalization g : {Globalization::line_search, Globalization::trust_region}) {
      r.solver.method = m;
      r.solver.globalization = g;
      const SolveResult result = solve(r);
      ASSERT_FALSE(result.trace.empty());
      EXPECT_NEAR(result.trace.front().residual, at_y0, 1e-12 * (1 + at_y0)) << to_string(m) << " " << to_string(g);
    }
  }
}

TEST(SolveStart, Y0MustBeInTheComponentOfZ) {
  SolveRequest r;
  r.problem.n = 3;
  const MatrixXd z = start_point(3, r.problem.seed);
  auto field = [&](const MatrixXd& y0) {
    r.y0 = y0;
    try {
      validate(r);
    } catch (const RequestError& e) {
      return e.field() + (e.kind() == RequestError::Kind::unprocessable ? " 422" : " 400");
    }
    return std::string("valid");
  };
  EXPECT_EQ(field(z * so3::exp(Vector3d(0.3, -2, 1))), "valid");
  EXPECT_EQ(field(MatrixXd::Identity(4, 4)), "y0 400");
  EXPECT_EQ(field(2 * z), "y0 422");                  // not orthogonal
  EXPECT_EQ(field(-z), "y0 422");                     // det(z^-1 y0) = -1: not reachable from z
  MatrixXd nan = z;
  nan(0, 0) = std::nan("");
  EXPECT_EQ(field(nan), "y0 400");
}

TEST(SolveStart, StartOnTheEdgeOfLogsDomainIsReportedNotCrashed) {
  SolveRequest r;
  r.problem.n = 3;
  r.h = 0.5;
  const MatrixXd z = start_point(3, r.problem.seed);
  r.y0 = MatrixXd(z * so3::exp(Vector3d(std::numbers::pi, 0, 0)));  // z^-1 y0 a half turn: log undefined
  for (Method m : kAllMethods) {
    r.solver.method = m;
    const SolveResult res = solve(r);
    EXPECT_EQ(res.status, Status::left_log_domain) << to_string(m) << ": " << res.reason;
    EXPECT_TRUE(res.y.allFinite());
    EXPECT_LT((res.y - *r.y0).norm(), 1e-12);
  }
}

}  // namespace
}  // namespace lienewton
