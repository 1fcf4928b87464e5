#pragma once
// Every request on one group G: what register_group<Family>() (register_group.hpp) compiles for each group of a
// family. The requests' own files (solve.cpp, basins.cpp, integrate.cpp, reference_solution.cpp) validate and
// reach these through the group registry (group_registry.hpp).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <string>

#include "basin_map.hpp"
#include "cancellation.hpp"
#include "cpu_clock.hpp"
#include "integrate.hpp"
#include "problems.hpp"
#include "reference_solution.hpp"
#include "solve.hpp"
#include "rkmk_tableau.hpp"
#include "solvers/rkmk_stages.hpp"
#include "solvers/run_method.hpp"
#include "step_size_control.hpp"
#include "user_field/user_vector_field.hpp"

namespace lienewton {

// solve(): the implicit Euler equation of the request's problem, from z (or y0), by the request's method.
template <LieGroup G>
SolveResult solve_on(const G& group, const SolveRequest& req, const TraceCallback& cb) {
  const auto field = make_field(group, req.problem);
  auto eq = Equation<G>::implicit_euler(group, group.element(req.problem.start()), req.h, *field);
  if (req.y0) eq.start_at(group.element(*req.y0));
  SolveResult result = run_method(req.solver.method, eq, req.solver, cb);
  if (result.status == Status::non_finite) {
    if (std::string why = off_algebra_reason(group, *field, result.total_iterations()); !why.empty())
      result.reason = std::move(why);
  }
  return result;
}

// basins(): the map of the request's implicit Euler equation over its plane of starts.
template <LieGroup G>
BasinResult basins_on(const G& group, const BasinRequest& req, const BasinRowCallback& on_row, const WorkFarm* farm) {
  const BasinGrid grid = basin_grid(req);
  const BasinPlane plane{grid.b1,      grid.b2,          req.size,    grid.radius,
                         req.methods,  req.solve.solver, req.threads, req.shard};
  const auto field = make_field(group, req.solve.problem);
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
  double a[3][3];
  double b[3];
  bool stiffly_accurate;  // b = a[stages - 1], so y_k+1 = Y_s
};

// Implicit Euler (1.1): one stage, a = b = 1.
inline constexpr DirkTableau kImplicitEuler{
    1, {{1.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}}, {1.0, 0.0, 0.0}, true};
// dirk-cg2: the L-stable SDIRK with gamma = 1 - 1/sqrt(2), c = (gamma, 1), b = last row of A (stiffly
// accurate, so y_k+1 = Y_2). Order 2: sum b = 1 and sum b_i c_i = (1-gamma) gamma + gamma = 1/2; for
// Crouch-Grossman methods the order conditions up to order 2 are the classical ones (the first conditions
// specific to the non-commutative setting appear at order 3, Owren & Marthinsen 1999).
inline constexpr double kGamma = 1.0 - 0.70710678118654752440;
inline constexpr DirkTableau kDirkCg2{
    2, {{kGamma, 0.0, 0.0}, {1.0 - kGamma, kGamma, 0.0}, {0.0, 0.0, 0.0}}, {1.0 - kGamma, kGamma, 0.0}, true};
// dirk-cg3: a three-stage SDIRK whose coefficients solve the order-3 conditions of Crouch-Grossman methods
// (Owren & Marthinsen, BIT 39 (1999)): the classical
//   sum b_i = 1, sum b_i c_i = 1/2, sum b_i c_i^2 = 1/3, sum b_i a_ij c_j = 1/6,
// and the one the non-commuting exponentials add,
//   sum b_i^2 c_i + 2 sum_{i<j} b_i c_i b_j = 1/3.
// With three stages and order 3 the stability function depends on gamma alone; gamma = 0.43586..., the root of
// 6 g^3 - 18 g^2 + 9 g - 1 of Alexander's L-stable SDIRK3 (SIAM J. Numer. Anal. 14 (1977)), makes it L-stable.
// That leaves a one-parameter family; c_2 = 1/5 picks one with c in [0, 1] and no coefficient above 0.62 in
// size, solved to rounding by Newton (docs/integrators.md). Not stiffly accurate: y_k+1 is the product of the b_i
// exponentials. Alexander's own tableau fails the last condition (its left side is 0.5017).
inline constexpr double kGamma3 = 0.43586652150845899941;
inline constexpr DirkTableau kDirkCg3{3,
                                      {{kGamma3, 0.0, 0.0},
                                       {-0.235866521508459, kGamma3, 0.0},
                                       {-0.24071786516339652, 0.548838495713276, kGamma3}},
                                      {-0.13948593195334003, 0.5275228363001196, 0.6119630956532204},
                                      false};

inline const DirkTableau& tableau_of(Integrator integrator) {
  return integrator == Integrator::dirk_cg3   ? kDirkCg3
         : integrator == Integrator::dirk_cg2 ? kDirkCg2
                                              : kImplicitEuler;
}

}  // namespace integration

namespace reference {

// One RKMK4 step from y at time t: stages in the algebra, each pulled back by dexpinv of its own offset.
template <LieGroup G>
typename G::Element rkmk4_step(const G& group, VectorField<G>& field, const typename G::Element& y, double t,
                               double h) {
  using Vector = typename G::Vector;
  auto stage = [&](const Vector& offset, double c) {
    field.set_time(t + c * h);
    const Vector g = field.g(group.times_exp(y, offset));
    return Vector(h * group.dexpinv(group.spectral(offset), g));
  };
  field.set_time(t);
  const Vector k1 = h * field.g(y);
  const Vector k2 = stage(0.5 * k1, 0.5);
  const Vector k3 = stage(0.5 * k2, 0.5);
  const Vector k4 = stage(k3, 1.0);
  return group.times_exp(y, (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0);
}

}  // namespace reference

// integrate(): the request's integrator. A DIRK method solves every stage equation by the request's method (section
// 6) at the root continued from its Z_i (continuation.hpp: the path from h = 0 of the stage, which starts at the
// explicit Lie-Euler value Z_i exp(h a_ii g(Z_i)), the tangent's prediction, unless the predictor is none). An
// implicit RKMK method solves its coupled stage system at the root continued from h = 0 (rkmk_stages.hpp), from the
// stages extrapolated from the previous step (lie-euler; none: from K = 0). rkmk4 is explicit.
// Fixed steps: a step whose stages cannot reach that root is taken again as two half steps, down to
// 2^-kMaxHalvings of the step, inside the same output step; failing that the integration ends with the stage's
// status, naming the step. Adaptive steps (rtol/atol, step_size_control.hpp): every try is one whole step and two
// half steps; it is rejected when the error estimate exceeds 1 or any of them fails, and the integration ends with
// min_step below the minimum step or max_steps at the bound on tries, naming t.
template <LieGroup G>
IntegrateResult integrate_on(const G& group, const IntegrateRequest& req, const Eigen::MatrixXd& y0,
                             const StepCallback& on_step) {
  using Element = typename G::Element;
  using Vector = typename G::Vector;
  constexpr int kMaxHalvings = 6;
  const auto field = make_field(group, req.problem);
  const integration::DirkTableau& tab = integration::tableau_of(req.integrator);
  SolverOptions opt = req.solver;
  opt.include_iterates = false;
  const int steps = static_cast<int>(std::llround(req.t_end / req.h));
  const double h = req.t_end / steps;
  // The invariants are read off each state the run returns or passes, never off the integrator's stages.
  const bool conserves = has_invariants(req.problem);
  const auto invariants = [&](const Element& y) {
    return conserves ? invariants_at(req.problem, group.matrix(y)) : InvariantValues{};
  };

  const std::optional<RkmkTableau> rkmk = rkmk_tableau(req.integrator);
  // The last start (t, g(t, y)) of a solved step: the RKMK predictor extrapolates g linearly from it (a secant
  // through a later point too: adaptive steps take the whole step after its two halves).
  std::optional<std::pair<double, Vector>> previous;
  // One step of size dt from y at time t: y_k+1, or nothing with rec's status and failure set by the failing stage.
  std::string failure;
  const auto rkmk_step = [&](const Element& y, double t, double dt, StepRecord& rec) -> std::optional<Element> {
    const RkmkStages<G> sys(group, *field, *rkmk, y, t, dt);
    const Vector g = sys.g_at_start();
    Eigen::VectorXd start = Eigen::VectorXd::Zero(sys.size());
    if (req.predictor != Predictor::none)
      start = previous && previous->first != t ? sys.along(g, Vector((g - previous->second) / (t - previous->first)))
                                               : sys.constant(g);
    const StageSolution stages = continued_stages(sys, start, opt.method, opt.differential, opt);
    rec.iterations += stages.iterations;
    rec.residual = std::max(rec.residual, stages.residual());
    if (!stages.continued) {
      rec.status = stages.status == Status::converged ? Status::fold : stages.status;
      failure = "stages (h = " + format_number(dt) + "): " + stages.reason;
      return std::nullopt;
    }
    previous.emplace(t, g);
    return sys.next(stages.k);
  };
  const auto explicit_step = [&](const Element& y, double t, double dt, StepRecord& rec) -> std::optional<Element> {
    Element next = reference::rkmk4_step(group, *field, y, t, dt);
    if (group.matrix(next).allFinite()) return next;
    rec.status = Status::non_finite;
    failure = "the explicit step (h = " + format_number(dt) + ") is not finite";
    return std::nullopt;
  };
  const auto dirk_step = [&](const Element& y, double t, double dt, StepRecord& rec) -> std::optional<Element> {
    Vector hg[3];
    Element last_stage;
    for (int i = 0; i < tab.stages; ++i) {
      double c = 0.0;  // the stage's time, as a fraction of dt: c_i = sum_j a_ij
      for (int j = 0; j <= i; ++j) c += tab.a[i][j];
      field->set_time(t + c * dt);
      Element z = y;
      for (int j = 0; j < i; ++j) z = group.times_exp(z, tab.a[i][j] * hg[j]);
      const auto eq = Equation<G>::implicit_euler(group, z, dt * tab.a[i][i], *field);
      const SolveResult stage = continued_root(opt.method, eq, opt, {}, req.predictor == Predictor::none);
      rec.iterations += stage.total_iterations();
      rec.residual = std::max(rec.residual, stage.residual);
      if (stage.status != Status::converged || stage.branch != Branch::continued) {
        rec.status = stage.status == Status::converged ? Status::fold : stage.status;
        failure = "stage " + std::to_string(i + 1) + " (h = " + format_number(dt) + "): " + stage.reason;
        return std::nullopt;
      }
      last_stage = group.element(stage.y);
      hg[i] = dt * field->g(last_stage);
    }
    // A stiffly accurate tableau's exp-products of the b_i are Y_s: taking Y_s saves s products and their
    // rounding (orthogonality drift over 1e4 steps drops ~10x).
    if (tab.stiffly_accurate) return last_stage;
    Element next = y;
    for (int i = 0; i < tab.stages; ++i) next = group.times_exp(next, tab.b[i] * hg[i]);
    return next;
  };
  const auto take = [&](const Element& y, double t, double dt, StepRecord& rec) -> std::optional<Element> {
    throw_if_cancelled();
    return rkmk                                  ? rkmk_step(y, t, dt, rec)
           : !solves_stages(req.integrator)      ? explicit_step(y, t, dt, rec)
                                                 : dirk_step(y, t, dt, rec);
  };
  // dt from y at time t, as one step or as two halves (recursively): y at the end, or nothing.
  const std::function<std::optional<Element>(const Element&, double, double, int, StepRecord&)> advance =
      [&](const Element& y, double t, double dt, int halvings, StepRecord& rec) -> std::optional<Element> {
    StepRecord attempt = rec;
    auto next = take(y, t, dt, attempt);
    if (next) {
      attempt.substeps = rec.substeps + 1;
      rec = attempt;
      return next;
    }
    rec.iterations = attempt.iterations;
    rec.residual = attempt.residual;
    if (halvings == kMaxHalvings || attempt.status == Status::cancelled) {
      rec.status = attempt.status;
      return std::nullopt;
    }
    const auto middle = advance(y, t, dt / 2, halvings + 1, rec);
    return middle ? advance(*middle, t + dt / 2, dt / 2, halvings + 1, rec) : std::nullopt;
  };

  IntegrateResult res;
  res.adaptive = req.adaptive();
  const double cpu_start = thread_cpu_seconds();
  Element y = group.element(y0);
  InvariantDrift drift(invariants(y), conserves ? invariant_scales(req.problem, y0) : InvariantValues{});
  // Frames: every frame_stride-th step and the last one. Adaptive steps, whose number is not known ahead, start
  // at every step and double the stride whenever more than 2 frames states are kept (thinning the kept ones).
  int frame_stride = req.frames > 0 ? (res.adaptive ? 1 : std::max(1, steps / req.frames)) : 0;
  if (frame_stride) {
    res.frames.push_back(group.matrix(y));
    res.frame_times.push_back(0.0);
    res.frame_steps.push_back(0);
  }
  const auto keep_frame = [&](int k, double t, bool last) {
    if (!frame_stride || (k % frame_stride != 0 && !last)) return;
    res.frames.push_back(group.matrix(y));
    res.frame_times.push_back(t);
    res.frame_steps.push_back(k);
    if (!res.adaptive || res.frames.size() <= 2 * static_cast<std::size_t>(req.frames) + 1) return;
    frame_stride *= 2;
    std::size_t kept = 0;
    for (std::size_t i = 0; i < res.frames.size(); ++i) {
      if (res.frame_steps[i] % frame_stride != 0 && !(last && i + 1 == res.frames.size())) continue;
      if (kept != i) res.frames[kept] = std::move(res.frames[i]);
      res.frame_times[kept] = res.frame_times[i];
      res.frame_steps[kept++] = res.frame_steps[i];
    }
    res.frames.resize(kept);
    res.frame_times.resize(kept);
    res.frame_steps.resize(kept);
  };
  // A step's record (y is its end state); false when the caller asks to stop.
  const auto record = [&](StepRecord& rec, bool last) {
    rec.invariants = invariants(y);
    drift.add(rec.invariants);
    res.orthogonality_error = std::max(res.orthogonality_error, group.defect(y));
    res.steps.push_back(rec);
    res.total_iterations += rec.iterations;
    res.substeps += rec.substeps;
    res.rejected += rec.rejected;
    keep_frame(rec.step, rec.t, last);
    return !on_step || on_step(rec);
  };
  const auto cancelled_after = [&](int k) {
    res.status = Status::cancelled;
    res.reason = "cancelled by the caller after step " + std::to_string(k);
  };

  if (!res.adaptive) {
    res.steps.reserve(static_cast<std::size_t>(steps));
    for (int k = 1; k <= steps; ++k) {
      StepRecord rec{.step = k, .t = k * h, .h = h};
      const auto next = advance(y, (k - 1) * h, h, 0, rec);
      if (next) y = *next;
      const bool keep_going = record(rec, k == steps);
      if (!next) {
        res.status = rec.status;
        // An explicit step has no branch to leave: it only overflows.
        const char* what = solves_stages(req.integrator) ? "did not stay on the solution's branch" : "overflowed";
        res.reason = "step " + std::to_string(k) + " (t = " + format_number((k - 1) * h) + " to " +
                     format_number(k * h) + ") " + what + ", even in " + std::to_string(1 << kMaxHalvings) +
                     " substeps: " + failure;
        break;
      }
      if (!keep_going) {
        cancelled_after(k);
        break;
      }
    }
  } else {
    const StepSizeControl control{req.rtol.value_or(req.atol.value_or(0.0)), req.atol.value_or(req.rtol.value_or(0.0)),
                                  order_of(req.integrator)};
    const double h_min = StepSizeControl::kMinStepFraction * req.t_end;
    double t = 0.0, dt = std::min(req.h, req.t_end);
    double h_smallest = req.t_end, h_largest = 0.0;
    bool after_rejection = false;
    int tries = 0;
    // t to 12 digits: where the steps fell below the minimum step, 3 digits would not tell t from a neighbour.
    const auto time_text = [](double x) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.12g", x);
      return std::string(buf);
    };
    StepRecord rec;  // the step being tried: the work of its rejected tries counts in it
    std::string why;  // the last rejection's cause
    while (t < req.t_end) {
      // The last step stretches to t_end rather than leave a sliver behind.
      if (req.t_end - t <= 1.1 * dt) dt = req.t_end - t;
      if (tries == req.max_steps) {
        res.status = Status::max_steps;
        res.reason = "max_steps = " + std::to_string(req.max_steps) + " tries (" + std::to_string(res.steps.size()) +
                     " accepted, " + std::to_string(res.rejected + rec.rejected) + " rejected) reached t = " +
                     time_text(t) + " of t_end = " + format_number(req.t_end);
        break;
      }
      if (dt < h_min && dt < req.t_end - t) {
        res.status = Status::min_step;
        res.reason = "at t = " + time_text(t) + " the step size fell to " + format_number(dt) +
                     ", below the minimum step " + format_number(h_min) + " (1e-10 t_end): " + why;
        break;
      }
      ++tries;
      StepRecord attempt = rec;
      attempt.status = Status::converged;
      const auto first = take(y, t, dt / 2, attempt);
      const auto second = first ? take(*first, t + dt / 2, dt / 2, attempt) : std::nullopt;
      const auto whole = second ? take(y, t, dt, attempt) : std::nullopt;
      rec.iterations = attempt.iterations;
      if (!whole) {
        ++rec.rejected;
        why = "the try at h = " + format_number(dt) + " failed (" + std::string(to_string(attempt.status)) +
              "): " + failure;
        dt *= StepSizeControl::kFailureFactor;
        after_rejection = true;
        continue;
      }
      const double err = control.error(group.matrix(y), group.matrix(*whole), group.matrix(*second));
      if (!(err <= 1.0)) {
        ++rec.rejected;
        why = "the error estimate at h = " + format_number(dt) + " is " + format_number(err);
        dt *= std::isfinite(err) ? control.factor(err, true) : StepSizeControl::kFailureFactor;
        after_rejection = true;
        continue;
      }
      y = *second;
      const bool last = dt == req.t_end - t;
      t = last ? req.t_end : t + dt;
      attempt.step = static_cast<int>(res.steps.size()) + 1;
      attempt.t = t;
      attempt.h = dt;
      attempt.error_estimate = err;
      attempt.substeps = 2;
      h_smallest = std::min(h_smallest, dt);
      h_largest = std::max(h_largest, dt);
      if (!record(attempt, last)) {
        cancelled_after(attempt.step);
        break;
      }
      rec = StepRecord{};
      dt *= control.factor(err, after_rejection);
      after_rejection = false;
    }
    if (res.status == Status::converged)
      res.reason = std::to_string(res.steps.size()) + " adaptive steps (" + std::to_string(res.rejected) +
                   " tries rejected), h from " + format_number(h_smallest) + " to " + format_number(h_largest) +
                   ", every error estimate <= 1 (rtol " + format_number(control.rtol) + ", atol " +
                   format_number(control.atol) + ")" +
                   (!solves_stages(req.integrator) ? std::string()
                                                   : "; every stage converged to the root continued from its start");
  }
  res.cpu_seconds = thread_cpu_seconds() - cpu_start;
  if (!res.steps.empty()) res.mean_iterations = double(res.total_iterations) / double(res.steps.size());
  res.y = group.matrix(y);
  res.initial_invariants = drift.initial();
  res.invariant_scales = drift.scales();
  res.invariant_drifts = drift.drift();
  if (res.status == Status::converged && !res.adaptive)
    res.reason = !solves_stages(req.integrator)
                     ? std::to_string(steps) + " explicit steps (" + std::to_string(res.substeps) + " substeps)"
                     : "every stage of " + std::to_string(steps) + " steps (" + std::to_string(res.substeps) +
                           " substeps) converged to the root continued from its start";
  return res;
}


// field_rate(): the field's speed and the size of its differential at y, whichever is larger.
template <LieGroup G>
double field_rate_on(const G& group, const ProblemSpec& problem, const Eigen::MatrixXd& y0) {
  const auto field = make_field(group, problem);
  const typename G::Element y = group.element(y0);
  return std::max(field->g(y).norm(), field->dg_matrix(group, y).norm());
}

// reference_solution(): RKMK4 at kReferenceStepsPerUnit steps per unit of time or more, the steps doubled until two
// successive finite solutions agree to kReferenceTolerance (RKMK4's error at the finer is about 1/15 of their
// distance): a fast field (the heavy top's spin of 150 rad/s) needs a hundred times the steps a slow one does, a
// stiff one (an eigenvalue -1e4) the steps that bring h |lambda| inside RKMK4's stability interval; its overflowing
// runs are skipped. Past kMaxReferenceSteps, rkmk-radau3 (L-stable) refined the same way from 64 steps.
template <LieGroup G>
ReferenceSolution reference_on(const G& group, const ProblemSpec& problem, const Eigen::MatrixXd& y0, double t_end) {
  const auto field = make_field(group, problem);
  const auto explicit_run = [&](long long steps) {
    const double h = t_end / static_cast<double>(steps);
    typename G::Element y = group.element(y0);
    for (long long k = 0; k < steps; ++k) {
      throw_if_cancelled();
      y = reference::rkmk4_step(group, *field, y, static_cast<double>(k) * h, h);
    }
    return group.matrix(y);
  };
  const auto implicit_run = [&](long long steps) -> Eigen::MatrixXd {
    IntegrateRequest req{.problem = problem, .h = t_end / static_cast<double>(steps), .t_end = t_end,
                         .integrator = Integrator::rkmk_radau3, .reference = false};
    req.solver.tol = 1e-12;
    const IntegrateResult r = integrate_on(group, req, y0, {});
    if (r.status != Status::converged) return Eigen::MatrixXd::Constant(y0.rows(), y0.cols(), NAN);
    return r.y;
  };
  // Doubles the steps of run from `steps` until two finite solutions agree to tolerance relative or max is reached.
  const auto refine = [&](const auto& run, long long steps, long long max, double tolerance,
                          const char* name) -> ReferenceSolution {
    Eigen::MatrixXd coarse = run(steps);
    while (steps < max) {
      steps *= 2;
      Eigen::MatrixXd fine = run(steps);
      if (fine.allFinite() && coarse.allFinite()) {
        const double distance = (fine - coarse).norm();
        if (distance <= tolerance * std::max(1.0, fine.norm()))
          return {std::move(fine), distance, std::string(name) + " at " + std::to_string(steps) + " steps"};
      }
      coarse = std::move(fine);
    }
    return {};
  };
  // The first comparison is against half the steps, so a slow field costs 1.5 times one run at
  // kReferenceStepsPerUnit, whose solution it returns.
  const long long first = std::max(32LL, static_cast<long long>(std::ceil(t_end * kReferenceStepsPerUnit / 2)));
  if (ReferenceSolution r = refine(explicit_run, first, kMaxReferenceSteps, kReferenceTolerance, "rkmk4"); r.y)
    return r;
  if (ReferenceSolution r = refine(implicit_run, 64, kMaxImplicitReferenceSteps, kImplicitReferenceTolerance,
                                   "rkmk-radau3");
      r.y)
    return r;
  return {.note = "no reference solution: rkmk4 up to " + std::to_string(kMaxReferenceSteps) +
                  " steps and rkmk-radau3 up to " + std::to_string(kMaxImplicitReferenceSteps) +
                  " steps did not settle (two refinements agreeing to " + format_number(kImplicitReferenceTolerance) +
                  ")"};
}

}  // namespace lienewton
