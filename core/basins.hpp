#pragma once
// Basin maps: from which starting guesses does each method converge, and to which root?
// For the implicit Euler equation f(y) = log(z^-1 y) - h g(y) = 0 (3.6) with the request's z, the start of
// every solve is moved over a plane of the group through z,
//   y_0(a, b) = z exp(a B1 + b B2),   (a, b) in [-r, r]^2 on a size x size grid of pixel centres,
// and each chosen method runs from each y_0 (Version 1 from y_0 (3.5), Version 2 from v_0 = log(z^-1 y_0)
// (3.20), the fixed point (1.2) from y_0). A pixel is converged to root k, or carries its failure Status.
// Roots are the converged y clustered by ||log(y_i^-1 y_j)|| < kRootDistance and numbered in pixel order
// (rows by b, then columns by a, then the request's method order), so the numbering is the same for any
// thread count: rows are clustered one after the other, in order, as they complete.
#include <Eigen/Dense>
#include <array>
#include <functional>
#include <optional>
#include <vector>

#include "shard.hpp"
#include "solve.hpp"
#include "status.hpp"
#include "work_farm.hpp"

namespace lienewton {

inline constexpr int kDefaultBasinSize = 128;
inline constexpr int kMaxBasinSize = 512;
inline constexpr double kRootDistance = 1e-8;

// A basin request is a solve request without its method (the equation: problem, N, h, z; and the solver
// options: differential, tol, ...) plus the plane of starts and the methods to run from each.
struct BasinRequest {
  SolveRequest solve{};  // its method, y0 and include_iterates are not used
  std::vector<Method> methods{std::begin(kAllMethods), std::end(kAllMethods)};
  int size = kDefaultBasinSize;     // pixels per side
  std::optional<double> radius;     // r; absent: the group's log radius (pi on SO(N))
  // B1, B2 as algebra coordinates (basis E_ij - E_ji), normalised before use; default the first two basis
  // elements.
  std::optional<Eigen::VectorXd> b1{}, b2{};
  int threads = 0;  // 0: all cores
  std::optional<Shard> shard;  // compute only this part's rows: basin_shard_rows(size, shard)
  // Opaque text that tells one map's requests from another's (the service: the request as read, without shard);
  // the result carries it, so merge_shards refuses parts of different maps with the same grid.
  std::string request_key;
};

// One pixel for one method.
struct BasinPixel {
  Status status = Status::max_iterations;
  int root = -1;       // the root's id when converged, else -1
  int iterations = 0;  // the solve's iterations (converged: the first n with ||f(y_n)|| <= tol)
};

struct BasinRoot {
  int id = 0;
  Eigen::MatrixXd y;          // the first converged y (in pixel order) of the cluster
  double residual = 0;        // ||f(y)|| of that y
  double distance_from_z = 0; // ||log(z^-1 y)||
  double hg_angle = 0;        // largest rotation angle of h g(y)
};

struct BasinRow {
  int row = 0;  // b index: b = -r + r (2 row + 1) / size
  double b = 0;
  std::vector<std::vector<BasinPixel>> pixels;  // [method][column]
  std::vector<int> new_roots;                   // ids of the roots first met in this row
};

struct BasinMethodSummary {
  Method method = Method::newton_group;
  int pixels = 0;
  int converged = 0;
  double converged_fraction = 0;
  int basins = 0;                         // distinct roots this method reached
  std::optional<double> mean_iterations;  // over the converged pixels
  std::array<int, std::size(kAllStatuses)> status_counts{};  // indexed like kAllStatuses
};

// Where the starts lie: y_0 = z exp(a b1 + b b2) for a in axis (columns) and b in axis (rows).
struct BasinGrid {
  std::vector<double> axis;  // pixel-centre coordinates, basin_axis(size, radius)
  double radius = 0;         // r
  Eigen::VectorXd b1, b2;    // the unit directions used (algebra coordinates)
  Eigen::MatrixXd z;         // the equation's z (after the z rule: the group's element nearest to it)
  std::string group = ProblemSpec{}.group;  // the family of z's group (its n: z's size)
};

struct BasinResult {
  BasinGrid grid;
  std::vector<BasinRow> rows; // in row order; a cancelled map holds the rows finished before the stop
  std::vector<BasinRoot> roots;
  std::vector<BasinMethodSummary> methods;
  bool complete = false;      // every row finished (of the part, when sharded)
  double seconds = 0;
  // A sharded map: its part. Its rows, roots and summaries are the part's alone (roots numbered in the part's
  // pixel order); merge_shards joins the parts.
  std::optional<Shard> shard;
  std::string request_key;  // the request's
};

// Checks the request; throws RequestError naming the field (size beyond kMaxBasinSize, radius, b1/b2 of the
// wrong length, zero or parallel, an algebra of one dimension, ...).
void validate(const BasinRequest& request);

// Called in row order, serialised, as each row is classified; return false to stop the map.
using BasinRowCallback = std::function<bool(const BasinRow& row, const std::vector<BasinRoot>& roots)>;

// Computes the map in parallel. Every solve polls the current cancellation token; a cancelled map returns the
// rows finished so far (complete = false). farm (optional): the rows are computed by its processes instead of
// request.threads threads here; a process that only computed rows for it gets an empty result.
BasinResult basins(const BasinRequest& request, const BasinRowCallback& on_row = {}, const WorkFarm* farm = nullptr);
// basins() of a request the caller has already validated: it is not checked again.
BasinResult basins_validated(const BasinRequest& request, const BasinRowCallback& on_row = {},
                             const WorkFarm* farm = nullptr);

// The rows part `shard` of a size x size map computes: r with r % count == index (all rows without a shard), so
// the parts' rows interleave and cost about the same.
std::vector<int> basin_shard_rows(int size, const std::optional<Shard>& shard);

// Per method (in `methods` order) its pixels, converged fraction, basins and mean iterations, summed over rows
// in row order, then columns.
std::vector<BasinMethodSummary> basin_summaries(const std::vector<BasinRow>& rows, const std::vector<Method>& methods);

// Joins the results of every shard of one basin map (any order) into the unsharded result: rows in order, roots
// renumbered in pixel order (a root's y is the one of the part holding its earliest pixel; parts' roots closer
// than kRootDistance are one), summaries recomputed, seconds summed. Throws RequestError (field "shard") when a
// part is missing, repeated, unsharded, incomplete, or from another map or sharding.
BasinResult merge_shards(const std::vector<BasinResult>& parts);

// The map's pixel-centre coordinates -r + r (2 i + 1) / size, i = 0..size-1.
std::vector<double> basin_axis(int size, double radius);
// The grid of a valid request, without solving anything (streams announce it before the first row).
BasinGrid basin_grid(const BasinRequest& request);

}  // namespace lienewton
