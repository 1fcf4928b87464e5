#pragma once
// Every request on one group G: what register_group<Family>() (register_group.hpp) compiles for each group of a
// family. The requests' own files (solve.cpp, basins.cpp, integrate.cpp, reference_solution.cpp) validate and
// reach these through the group registry (group_registry.hpp).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>

#include "basin_map.hpp"
#include "cancellation.hpp"
#include "cpu_clock.hpp"
#include "integrate.hpp"
#include "problems.hpp"
#include "reference_solution.hpp"
#include "solve.hpp"
#include "solvers/run_method.hpp"

namespace lienewton {

// solve(): the implicit Euler equation of the request's problem, from z (or y0), by the request's method.
template <LieGroup G>
SolveResult solve_on(const G& group, const SolveRequest& req, const TraceCallback& cb) {
  const auto field = make_field(group, req.problem.kind, req.problem.rigid_body);
  auto eq = Equation<G>::implicit_euler(group, group.element(req.problem.start()), req.h, *field);
  if (req.y0) eq.start_at(group.element(*req.y0));
  return run_method(req.solver.method, eq, req.solver, cb);
}

// basins(): the map of the request's implicit Euler equation over its plane of starts.
template <LieGroup G>
BasinResult basins_on(const G& group, const BasinRequest& req, const BasinRowCallback& on_row, const WorkFarm* farm) {
  const BasinGrid grid = basin_grid(req);
  const BasinPlane plane{grid.b1,      grid.b2,          req.size,    grid.radius,
                         req.methods,  req.solve.solver, req.threads, req.shard};
  const auto field = make_field(group, req.solve.problem.kind, req.solve.problem.rigid_body);
  const auto eq = Equation<G>::implicit_euler(group, group.element(req.solve.problem.start()), req.solve.h, *field);
  BasinResult result = basin_map(eq, plane, on_row, farm);
  result.grid.group = grid.group;
  return result;
}

namespace integration {

// A diagonally implicit Crouch-Grossman method (section 6): stage i solves
//   Y_i = Z_i exp(h a_ii g(Y_i)),  Z_i = y_k exp(h a_i1 g(Y_1)) ... exp(h a_i,i-1 g(Y_i-1)),
// and y_k+1 = y_k exp(h b_1 g(Y_1)) ... exp(h b_s g(Y_s)).
struct DirkTableau {
  int stages;
  double a[2][2];
  double b[2];  // = a[stages - 1]: stiffly accurate, which integrate_on relies on
};

// Implicit Euler (1.1): one stage, a = b = 1.
inline constexpr DirkTableau kImplicitEuler{1, {{1.0, 0.0}, {0.0, 0.0}}, {1.0, 0.0}};
// dirk-cg2: the L-stable SDIRK with gamma = 1 - 1/sqrt(2), c = (gamma, 1), b = last row of A (stiffly
// accurate, so y_k+1 = Y_2). Order 2: sum b = 1 and sum b_i c_i = (1-gamma) gamma + gamma = 1/2; for
// Crouch-Grossman methods the order conditions up to order 2 are the classical ones (the first conditions
// specific to the non-commutative setting appear at order 3, Owren & Marthinsen 1999).
inline constexpr double kGamma = 1.0 - 0.70710678118654752440;
inline constexpr DirkTableau kDirkCg2{2, {{kGamma, 0.0}, {1.0 - kGamma, kGamma}}, {1.0 - kGamma, kGamma}};

inline const DirkTableau& tableau_of(Integrator integrator) {
  return integrator == Integrator::dirk_cg2 ? kDirkCg2 : kImplicitEuler;
}

// The explicit Lie-Euler predictor Z exp(h a_ii g(Z)) of the stage equation Y = Z exp(h a_ii g(Y)) (section 6):
// its residual f(Y_pred) = log(Z^-1 Y_pred) - h a_ii g(Y_pred) = h a_ii (g(Z) - g(Y_pred)) is O(h^2), while the
// paper's start Z has f(Z) = -h a_ii g(Z), O(h). Kept only when its residual is the smaller: never a worse start.
template <class G>
void start_at_lie_euler(Equation<G>& eq, const VectorField<G>& field) {
  const typename G::Vector hg = eq.h() * field.g(eq.z());
  const typename G::Element predicted = eq.group().times_exp(eq.z(), hg);
  const auto at_predicted = eq.at(predicted, Equation<G>::Need::residual);
  if (at_predicted.in_domain && at_predicted.residual < hg.norm()) eq.start_at(predicted);
}

inline Status worse(Status a, Status b) { return a == Status::converged ? b : a; }

}  // namespace integration

// integrate(): the request's integrator, every stage equation solved by the request's method (section 6).
template <LieGroup G>
IntegrateResult integrate_on(const G& group, const IntegrateRequest& req, const Eigen::MatrixXd& y0,
                             const StepCallback& on_step) {
  using Element = typename G::Element;
  using Vector = typename G::Vector;
  const auto field = make_field(group, req.problem.kind, req.problem.rigid_body);
  const integration::DirkTableau& tab = integration::tableau_of(req.integrator);
  SolverOptions opt = req.solver;
  opt.include_iterates = false;
  const int steps = static_cast<int>(std::llround(req.t_end / req.h));
  const double h = req.t_end / steps;
  const RigidBody* body = req.problem.kind == ProblemKind::rigid_body
                              ? &static_cast<const VectorFieldOf<G, RigidBody>&>(*field).problem()
                              : nullptr;
  auto energy = [&](const Element& y) { return body ? body->energy(Eigen::Matrix3d(y)) : 0.0; };

  IntegrateResult res;
  const double cpu_start = thread_cpu_seconds();
  Element y = group.element(y0);
  const double e0 = energy(y);
  double drift = 0.0;
  const int frame_every = req.frames > 0 ? std::max(1, steps / req.frames) : 0;
  if (frame_every) {
    res.frames.push_back(group.matrix(y));
    res.frame_times.push_back(0.0);
    res.frame_steps.push_back(0);
  }
  res.steps.reserve(static_cast<std::size_t>(steps));
  for (int k = 1; k <= steps; ++k) {
    StepRecord rec{k, k * h, 0, 0.0, Status::converged, 0.0};
    Vector hg[2];
    Element last_stage;
    for (int i = 0; i < tab.stages; ++i) {
      Element z = y;
      for (int j = 0; j < i; ++j) z = group.times_exp(z, tab.a[i][j] * hg[j]);
      auto eq = Equation<G>::implicit_euler(group, z, h * tab.a[i][i], *field);
      if (req.predictor == Predictor::lie_euler) integration::start_at_lie_euler(eq, *field);
      const SolveResult stage = run_method(opt.method, eq, opt, {});
      rec.iterations += stage.total_iterations();
      rec.residual = std::max(rec.residual, stage.residual);
      rec.status = integration::worse(rec.status, stage.status);
      if (stage.status != Status::converged) {
        res.reason = "step " + std::to_string(k) + ", stage " + std::to_string(i + 1) + ": " + stage.reason;
        break;
      }
      last_stage = group.element(stage.y);
      hg[i] = h * field->g(last_stage);
    }
    // Both tableaus are stiffly accurate (b = last row of A), so y_k+1 = exp-products of the b_i = Y_s:
    // taking Y_s saves s products and their rounding (orthogonality drift over 1e4 steps drops ~10x).
    if (rec.status == Status::converged) y = last_stage;
    rec.energy = energy(y);
    if (body) drift = std::max(drift, std::abs(rec.energy - e0) / e0);
    res.orthogonality_error = std::max(res.orthogonality_error, group.defect(y));
    res.steps.push_back(rec);
    res.total_iterations += rec.iterations;
    if (frame_every && (k % frame_every == 0 || k == steps)) {
      res.frames.push_back(group.matrix(y));
      res.frame_times.push_back(k * h);
      res.frame_steps.push_back(k);
    }
    const bool keep_going = !on_step || on_step(rec);
    if (rec.status != Status::converged) {
      res.status = rec.status;
      break;
    }
    if (!keep_going) {
      res.status = Status::cancelled;
      res.reason = "cancelled by the caller after step " + std::to_string(k);
      break;
    }
  }
  res.cpu_seconds = thread_cpu_seconds() - cpu_start;
  if (!res.steps.empty()) res.mean_iterations = double(res.total_iterations) / double(res.steps.size());
  res.y = group.matrix(y);
  if (body) {
    res.energy_drift = drift;
    res.initial_energy = e0;
  }
  if (res.status == Status::converged) res.reason = "every stage of " + std::to_string(steps) + " steps converged";
  return res;
}


namespace reference {

// One RKMK4 step: stages in the algebra, each pulled back by dexpinv of its own offset.
template <LieGroup G>
typename G::Element rkmk4_step(const G& group, const VectorField<G>& field, const typename G::Element& y, double h) {
  using Vector = typename G::Vector;
  auto stage = [&](const Vector& offset) {
    const Vector g = field.g(group.times_exp(y, offset));
    return Vector(h * group.dexpinv(group.spectral(offset), g));
  };
  const Vector k1 = h * field.g(y);
  const Vector k2 = stage(0.5 * k1);
  const Vector k3 = stage(0.5 * k2);
  const Vector k4 = stage(k3);
  return group.times_exp(y, (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0);
}

}  // namespace reference

// reference_solution(): RKMK4 at kReferenceStepsPerUnit steps per unit of time.
template <LieGroup G>
Eigen::MatrixXd reference_on(const G& group, const ProblemSpec& problem, const Eigen::MatrixXd& y0, double t_end) {
  const auto field = make_field(group, problem.kind, problem.rigid_body);
  const int steps = std::max(64, static_cast<int>(std::ceil(t_end * kReferenceStepsPerUnit)));
  const double h = t_end / steps;
  typename G::Element y = group.element(y0);
  for (int k = 0; k < steps; ++k) {
    throw_if_cancelled();
    y = reference::rkmk4_step(group, *field, y, h);
  }
  return group.matrix(y);
}

}  // namespace lienewton
