#include "basins.hpp"

#include <algorithm>
#include <chrono>
#include <cctype>
#include <cmath>
#include <set>

#include "basin_map.hpp"
#include "group_registry.hpp"
#include "parallel_for.hpp"
#include "validation.hpp"

namespace lienewton {
namespace {

constexpr double kMaxRadius = 100.0;  // exp of a compact group is periodic: a larger plane only repeats itself
// cos of the angle below which B1 and B2 count as parallel (the plane would be a line).
constexpr double kParallelCosine = 1.0 - 1e-12;

// Unit direction: the given coordinates, or basis element `index` of the algebra.
Eigen::VectorXd direction(const std::optional<Eigen::VectorXd>& given, int dim, int index) {
  if (given) return given->normalized();
  return Eigen::VectorXd::Unit(dim, index);
}

void check_direction(const std::optional<Eigen::VectorXd>& b, const std::string& field, int dim,
                     const std::string& dim_formula) {
  if (!b) return;
  if (b->size() != dim)
    validation::unprocessable(field, field + " must have " + std::to_string(dim) + " coordinates (the dimension " +
                                         dim_formula + " of the algebra)");
  if (!b->allFinite()) validation::invalid(field, field + " must have finite coordinates");
  if (!(b->norm() > 0)) validation::unprocessable(field, field + " must not be zero");
}

// The request-model accessors: the one place that knows how a SolveRequest spells its problem and options.
int dimension_of(const BasinRequest& req) { return req.solve.problem.n; }
Eigen::MatrixXd z_of(const BasinRequest& req) { return req.solve.problem.start(); }
const GroupFamily& family_of(const BasinRequest& req) { return req.solve.problem.family(); }
double radius_of(const BasinRequest& req) { return req.radius.value_or(family_of(req).log_radius()); }

}  // namespace

template BasinResult basin_map<SO3Group>(const Equation<SO3Group>&, const BasinPlane&, const BasinRowCallback&,
                                         const WorkFarm*);
template BasinResult basin_map<SONGroup>(const Equation<SONGroup>&, const BasinPlane&, const BasinRowCallback&,
                                         const WorkFarm*);

std::vector<double> basin_axis(int size, double radius) {
  std::vector<double> axis(static_cast<std::size_t>(size));
  for (int i = 0; i < size; ++i) axis[static_cast<std::size_t>(i)] = radius * (2.0 * i + 1.0 - size) / size;
  return axis;
}

BasinGrid basin_grid(const BasinRequest& req) {
  const GroupFamily& family = family_of(req);
  const int n = dimension_of(req), dim = family.algebra_dim(n);
  return {basin_axis(req.size, radius_of(req)), radius_of(req), direction(req.b1, dim, 0), direction(req.b2, dim, 1),
          family.project(n, z_of(req)), family.name()};
}

void validate(const BasinRequest& req) {
  SolveRequest equation = req.solve;
  equation.y0.reset();  // every pixel has its own start
  validate(equation);
  if (req.threads < 0) validation::invalid("threads", "threads must be >= 0");
  // The map's pixels run on up to `threads` threads at once, each with its own workspace for g.
  validation::check_workspace(equation.problem, resolve_thread_count(req.threads));
  const int n = dimension_of(req);
  const GroupFamily& family = family_of(req);
  const int dim = family.algebra_dim(n);
  if (dim < 2) {
    int least = n + 1;
    while (family.algebra_dim(least) < 2) ++least;
    std::string algebra = family.title(n);
    std::transform(algebra.begin(), algebra.end(), algebra.begin(), [](unsigned char c) { return std::tolower(c); });
    validation::unprocessable("n", "a basin map needs a plane in the algebra: n must be at least " +
                                       std::to_string(least) + " (" + algebra + " has dimension " +
                                       std::to_string(dim) + ")");
  }
  if (req.methods.empty()) validation::invalid("methods", "methods must name at least one method");
  for (std::size_t i = 0; i < req.methods.size(); ++i)
    if (std::find(req.methods.begin(), req.methods.begin() + static_cast<std::ptrdiff_t>(i), req.methods[i]) !=
        req.methods.begin() + static_cast<std::ptrdiff_t>(i))
      validation::invalid("methods", "methods must not repeat a method");
  if (req.size < 1) validation::invalid("size", "size must be an integer in [1, " + std::to_string(kMaxBasinSize) + "]");
  if (req.size > kMaxBasinSize)
    validation::unprocessable("size", "size " + std::to_string(req.size) + " is beyond the largest basin map, " +
                                          std::to_string(kMaxBasinSize) + " x " + std::to_string(kMaxBasinSize));
  const double radius = radius_of(req);
  if (!std::isfinite(radius) || !(radius > 0) || radius > kMaxRadius)
    validation::invalid("r", "r must be a finite number in (0, 100]");
  check_direction(req.b1, "b1", dim, family.algebra_dimension());
  check_direction(req.b2, "b2", dim, family.algebra_dimension());
  const Eigen::VectorXd b1 = direction(req.b1, dim, 0), b2 = direction(req.b2, dim, 1);
  if (std::abs(b1.dot(b2)) > kParallelCosine)
    validation::unprocessable(req.b2 ? "b2" : "b1", "b1 and b2 are parallel: they span no plane");
  if (req.shard && !(req.shard->count >= 1)) validation::invalid("shard.count", "shard.count must be at least 1");
  if (req.shard && !(req.shard->index >= 0 && req.shard->index < req.shard->count))
    validation::unprocessable("shard.index", "shard.index must be in [0, shard.count)");
}

BasinResult basins(const BasinRequest& req, const BasinRowCallback& on_row, const WorkFarm* farm) {
  validate(req);
  return basins_validated(req, on_row, farm);
}

BasinResult basins_validated(const BasinRequest& req, const BasinRowCallback& on_row, const WorkFarm* farm) {
  const auto start = std::chrono::steady_clock::now();
  BasinResult result = family_of(req).basins(req, on_row, farm);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.request_key = req.request_key;
  return result;
}

std::vector<int> basin_shard_rows(int size, const std::optional<Shard>& shard) {
  std::vector<int> rows;
  const int index = shard ? shard->index : 0, count = shard ? shard->count : 1;
  for (int r = index; r < size; r += count) rows.push_back(r);
  return rows;
}

std::vector<BasinMethodSummary> basin_summaries(const std::vector<BasinRow>& rows, const std::vector<Method>& methods) {
  std::vector<BasinMethodSummary> summaries;
  for (std::size_t m = 0; m < methods.size(); ++m) {
    BasinMethodSummary s;
    s.method = methods[m];
    std::set<int> reached;
    double iterations = 0;
    for (const BasinRow& row : rows) {
      for (const BasinPixel& p : row.pixels[m]) {
        ++s.pixels;
        const auto status = static_cast<std::size_t>(std::find(std::begin(kAllStatuses), std::end(kAllStatuses),
                                                               p.status) - std::begin(kAllStatuses));
        ++s.status_counts[status];
        if (p.status != Status::converged) continue;
        ++s.converged;
        iterations += p.iterations;
        reached.insert(p.root);
      }
    }
    s.basins = static_cast<int>(reached.size());
    if (s.pixels > 0) s.converged_fraction = static_cast<double>(s.converged) / s.pixels;
    if (s.converged > 0) s.mean_iterations = iterations / s.converged;
    summaries.push_back(s);
  }
  return summaries;
}

namespace {

std::vector<Method> methods_of(const BasinResult& map) {
  std::vector<Method> methods;
  for (const BasinMethodSummary& s : map.methods) methods.push_back(s.method);
  return methods;
}

bool same_grid(const BasinGrid& a, const BasinGrid& b) {
  return a.axis == b.axis && a.radius == b.radius && a.b1 == b.b1 && a.b2 == b.b2 && a.z == b.z && a.group == b.group;
}

// Checks that parts are every shard of one map, each once and complete; returns, per row of the map, the part
// holding it.
std::vector<std::size_t> row_owners(const std::vector<BasinResult>& parts) {
  if (parts.empty() || !parts.front().shard) validation::invalid("shard", "merge needs the results of a sharded basin map");
  const BasinResult& first = parts.front();
  const int count = first.shard->count;
  const std::size_t size = first.grid.axis.size();
  std::vector<char> have_part(static_cast<std::size_t>(count), 0);
  std::vector<std::size_t> owner(size, parts.size());
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const BasinResult& part = parts[k];
    if (!part.shard) validation::invalid("shard", "a basin map without shard is not part of a sharded map");
    if (part.shard->count != count || !same_grid(part.grid, first.grid) || methods_of(part) != methods_of(first) ||
        part.request_key != first.request_key)
      validation::invalid("shard", "the basin maps come from different maps or shardings");
    const int index = part.shard->index;
    if (index < 0 || index >= count) validation::invalid("shard", "shard index out of range");
    if (have_part[static_cast<std::size_t>(index)]++)
      validation::invalid("shard", "shard " + std::to_string(index) + " is given twice");
    if (!part.complete) validation::invalid("shard", "shard " + std::to_string(index) + " stopped early");
    std::vector<int> held;
    for (const BasinRow& row : part.rows) held.push_back(row.row);
    if (held != basin_shard_rows(static_cast<int>(size), part.shard))
      validation::invalid("shard", "shard " + std::to_string(index) + " does not hold its rows");
    for (const BasinRow& row : part.rows)
      if (row.pixels.size() != first.methods.size() ||
          std::any_of(row.pixels.begin(), row.pixels.end(), [&](const auto& p) { return p.size() != size; }))
        validation::invalid("shard", "row " + std::to_string(row.row) + " of shard " + std::to_string(index) +
                                         " does not have a pixel per column and method");
    for (int r : held) owner[static_cast<std::size_t>(r)] = k;
  }
  for (int i = 0; i < count; ++i)
    if (!have_part[static_cast<std::size_t>(i)])
      validation::invalid("shard", "shard " + std::to_string(i) + " of " + std::to_string(count) + " is missing");
  return owner;
}

}  // namespace

BasinResult merge_shards(const std::vector<BasinResult>& parts) {
  const std::vector<std::size_t> owner = row_owners(parts);
  const std::vector<Method> methods = methods_of(parts.front());
  BasinResult merged;
  merged.grid = parts.front().grid;
  merged.complete = true;
  for (const BasinResult& part : parts) merged.seconds += part.seconds;
  // The parts' root ids, in the order the unsharded map meets them (pixel order), mapped to global ids.
  std::vector<std::vector<int>> global_id(parts.size());
  std::vector<std::size_t> next_row(parts.size(), 0);
  for (std::size_t k = 0; k < parts.size(); ++k) global_id[k].assign(parts[k].roots.size(), -1);
  const GroupFamily& family = group_family(merged.grid.group);
  const int n = static_cast<int>(merged.grid.z.rows());
  const auto global_root = [&](std::size_t k, int local, std::vector<int>& new_roots) {
    if (local < 0 || local >= static_cast<int>(parts[k].roots.size()))
      validation::invalid("shard", "a pixel of shard " + std::to_string(parts[k].shard->index) + " names no root");
    int& id = global_id[k][static_cast<std::size_t>(local)];
    if (id >= 0) return id;
    const BasinRoot& root = parts[k].roots[static_cast<std::size_t>(local)];
    for (std::size_t i = 0; i < merged.roots.size() && id < 0; ++i)
      if (family.same_root(n, merged.roots[i].y, root.y)) id = static_cast<int>(i);
    if (id >= 0) return id;
    id = static_cast<int>(merged.roots.size());
    merged.roots.push_back(root);
    merged.roots.back().id = id;
    new_roots.push_back(id);
    return id;
  };
  for (std::size_t r = 0; r < owner.size(); ++r) {
    const std::size_t k = owner[r];
    BasinRow row = parts[k].rows[next_row[k]++];
    row.new_roots.clear();
    for (std::size_t column = 0; column < merged.grid.axis.size(); ++column)
      for (auto& pixels : row.pixels)
        if (pixels[column].status == Status::converged)
          pixels[column].root = global_root(k, pixels[column].root, row.new_roots);
    merged.rows.push_back(std::move(row));
  }
  merged.methods = basin_summaries(merged.rows, methods);
  return merged;
}

}  // namespace lienewton
