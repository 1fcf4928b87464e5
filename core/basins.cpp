#include "basins.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "basin_map.hpp"
#include "groups/polar_factor.hpp"
#include "groups/with_group.hpp"
#include "problems.hpp"
#include "validation.hpp"

namespace lienewton {
namespace {

constexpr double kMaxRadius = 100.0;  // exp is periodic: a larger plane only repeats itself
// cos of the angle below which B1 and B2 count as parallel (the plane would be a line).
constexpr double kParallelCosine = 1.0 - 1e-12;

// Unit direction: the given coordinates, or basis element `index` of the algebra.
Eigen::VectorXd direction(const std::optional<Eigen::VectorXd>& given, int dim, int index) {
  if (given) return given->normalized();
  return Eigen::VectorXd::Unit(dim, index);
}

void check_direction(const std::optional<Eigen::VectorXd>& b, const std::string& field, int dim) {
  if (!b) return;
  if (b->size() != dim)
    validation::unprocessable(field, field + " must have " + std::to_string(dim) +
                                         " coordinates (the dimension N(N-1)/2 of the algebra)");
  if (!b->allFinite()) validation::invalid(field, field + " must have finite coordinates");
  if (!(b->norm() > 0)) validation::unprocessable(field, field + " must not be zero");
}

// The request-model accessors: the one place that knows how a SolveRequest spells its problem and options.
int dimension_of(const BasinRequest& req) { return req.solve.problem.n; }
Eigen::MatrixXd z_of(const BasinRequest& req) { return req.solve.problem.start(); }
SolverOptions solver_of(const BasinRequest& req) { return req.solve.solver; }
template <class G>
std::unique_ptr<VectorField<G>> field_of(const G& group, const BasinRequest& req) {
  return make_field(group, req.solve.problem.kind, req.solve.problem.rigid_body);
}

}  // namespace

std::vector<double> basin_axis(int size, double radius) {
  std::vector<double> axis(static_cast<std::size_t>(size));
  for (int i = 0; i < size; ++i) axis[static_cast<std::size_t>(i)] = radius * (2.0 * i + 1.0 - size) / size;
  return axis;
}

BasinGrid basin_grid(const BasinRequest& req) {
  const int dim = dimension_of(req) * (dimension_of(req) - 1) / 2;
  return {basin_axis(req.size, req.radius), req.radius, direction(req.b1, dim, 0), direction(req.b2, dim, 1),
          orthogonal_polar_factor(z_of(req))};
}

void validate(const BasinRequest& req) {
  SolveRequest equation = req.solve;
  equation.y0.reset();  // every pixel has its own start
  validate(equation);
  const int n = dimension_of(req);
  if (n < 3) validation::unprocessable("n", "a basin map needs a plane in the algebra: n must be at least 3 (so(2) has dimension 1)");
  if (req.methods.empty()) validation::invalid("methods", "methods must name at least one method");
  for (std::size_t i = 0; i < req.methods.size(); ++i)
    if (std::find(req.methods.begin(), req.methods.begin() + static_cast<std::ptrdiff_t>(i), req.methods[i]) !=
        req.methods.begin() + static_cast<std::ptrdiff_t>(i))
      validation::invalid("methods", "methods must not repeat a method");
  if (req.size < 1) validation::invalid("size", "size must be an integer in [1, " + std::to_string(kMaxBasinSize) + "]");
  if (req.size > kMaxBasinSize)
    validation::unprocessable("size", "size " + std::to_string(req.size) + " is beyond the largest basin map, " +
                                          std::to_string(kMaxBasinSize) + " x " + std::to_string(kMaxBasinSize));
  if (!std::isfinite(req.radius) || !(req.radius > 0) || req.radius > kMaxRadius)
    validation::invalid("r", "r must be a finite number in (0, 100]");
  const int dim = n * (n - 1) / 2;
  check_direction(req.b1, "b1", dim);
  check_direction(req.b2, "b2", dim);
  const Eigen::VectorXd b1 = direction(req.b1, dim, 0), b2 = direction(req.b2, dim, 1);
  if (std::abs(b1.dot(b2)) > kParallelCosine)
    validation::unprocessable(req.b2 ? "b2" : "b1", "b1 and b2 are parallel: they span no plane");
  if (req.threads < 0) validation::invalid("threads", "threads must be >= 0");
}

BasinResult basins(const BasinRequest& req, const BasinRowCallback& on_row, const WorkFarm* farm) {
  validate(req);
  const auto start = std::chrono::steady_clock::now();
  const BasinGrid grid = basin_grid(req);
  const BasinPlane plane{grid.b1, grid.b2, req.size, req.radius, req.methods, solver_of(req), req.threads};
  BasinResult result = with_group(dimension_of(req), [&](const auto& group) {
    using G = std::decay_t<decltype(group)>;
    const auto field = field_of(group, req);
    const auto eq = Equation<G>::implicit_euler(group, typename G::Element(z_of(req)), req.solve.h, *field);
    return basin_map(eq, plane, on_row, farm);
  });
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace lienewton
