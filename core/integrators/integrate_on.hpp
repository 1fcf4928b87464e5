#pragma once
// integrate_on(): the request's integrator on group G, by fixed or adaptive steps (stepper.hpp takes each step).
// Fixed steps: a step whose stages cannot reach the continued root is taken again as two half steps, down to
// 2^-kMaxHalvings of the step, inside the same output step; failing that the integration ends with the stage's
// status, naming the step. Adaptive steps (rtol/atol, step_size_control.hpp): every try is one whole step and two
// half steps (step doubling), or, for an implicit RKMK method on a stiff step (Stepper::stiff), one step with
// its embedded estimate (embedded_estimate.hpp); it is rejected when the error estimate exceeds 1 or a step fails,
// and the integration ends with min_step below the minimum step or max_steps at the bound on tries, naming t.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "core/cpu_clock.hpp"
#include "core/integrate.hpp"
#include "core/step_size_control.hpp"
#include "core/user_field/user_vector_field.hpp"
#include "methods.hpp"
#include "stepper.hpp"

namespace lienewton {
namespace integrators {

template <LieGroup G>
class Integration {
 public:
  using Element = typename G::Element;

  Integration(const G& group, const IntegrateRequest& req, const Eigen::MatrixXd& y0, const StepCallback& on_step)
      : group_(group), req_(req), on_step_(on_step), field_(make_field(group, req.problem)),
        tab_(tableau_of(req.integrator)), stepper_(group, *field_, tab_, stage_options(req.solver), req.predictor),
        conserves_(has_invariants(req.problem)), y_(group.element(y0)),
        drift_(invariants(y_), conserves_ ? invariant_scales(req.problem, y0) : InvariantValues{}) {
    res_.adaptive = req.adaptive();
  }

  IntegrateResult run() {
    const double cpu_start = thread_cpu_seconds();
    const int steps = static_cast<int>(std::llround(req_.t_end / *req_.h));
    // Frames: every frame_stride-th step and the last one. Adaptive steps, whose number is not known ahead, start
    // at every step and double the stride whenever more than 2 frames states are kept (thinning the kept ones).
    frame_stride_ = req_.frames > 0 ? (res_.adaptive ? 1 : std::max(1, steps / req_.frames)) : 0;
    if (frame_stride_) keep(0, 0.0);
    if (res_.adaptive)
      adaptive_steps();
    else
      fixed_steps(steps);
    res_.cpu_seconds = thread_cpu_seconds() - cpu_start;
    res_.linear_solver = stepper_.factorization();
    if (!res_.steps.empty()) res_.mean_iterations = double(res_.total_iterations) / double(res_.steps.size());
    res_.y = group_.matrix(y_);
    res_.initial_invariants = drift_.initial();
    res_.invariant_scales = drift_.scales();
    res_.invariant_drifts = drift_.drift();
    return std::move(res_);
  }

 private:
  static constexpr int kMaxHalvings = 6;

  static SolverOptions stage_options(SolverOptions opt) {
    opt.include_iterates = false;
    return opt;
  }

  // The invariants are read off each state the run returns or passes, never off the integrator's stages.
  InvariantValues invariants(const Element& y) const {
    return conserves_ ? invariants_at(req_.problem, group_.matrix(y)) : InvariantValues{};
  }

  // dt from y at time t, as one step or as two halves (recursively): y at the end, or nothing.
  std::optional<Element> advance(const Element& y, double t, double dt, int halvings, StepRecord& rec) {
    StepRecord attempt = rec;
    auto next = stepper_.take(y, t, dt, attempt);
    if (next) {
      attempt.substeps = rec.substeps + 1;
      rec = attempt;
      return next;
    }
    rec.iterations = attempt.iterations;
    rec.jacobian_evaluations = attempt.jacobian_evaluations;
    rec.factorizations = attempt.factorizations;
    rec.residual = attempt.residual;
    if (halvings == kMaxHalvings || attempt.status == Status::cancelled) {
      rec.status = attempt.status;
      return std::nullopt;
    }
    const auto middle = advance(y, t, dt / 2, halvings + 1, rec);
    return middle ? advance(*middle, t + dt / 2, dt / 2, halvings + 1, rec) : std::nullopt;
  }

  void fixed_steps(int steps) {
    const double h = req_.t_end / steps;
    res_.steps.reserve(static_cast<std::size_t>(steps));
    for (int k = 1; k <= steps; ++k) {
      StepRecord rec{.step = k, .t = k * h, .h = h};
      const auto next = advance(y_, (k - 1) * h, h, 0, rec);
      if (next) y_ = *next;
      const bool keep_going = record(rec, k == steps);
      if (!next) {
        res_.status = rec.status;
        // An explicit step has no branch to leave: it only overflows.
        const char* what = tab_.solves_stages() ? "did not stay on the solution's branch" : "overflowed";
        res_.reason = "step " + std::to_string(k) + " (t = " + format_number((k - 1) * h) + " to " +
                      format_number(k * h) + ") " + what + ", even in " + std::to_string(1 << kMaxHalvings) +
                      " substeps: " + stepper_.failure();
        return;
      }
      if (!keep_going) return cancelled_after(k);
    }
    res_.reason = !tab_.solves_stages()
                      ? std::to_string(steps) + " explicit steps (" + std::to_string(res_.substeps) + " substeps)"
                      : "every stage of " + std::to_string(steps) + " steps (" + std::to_string(res_.substeps) +
                            " substeps) converged to the root continued from its start";
  }

  // One adaptive try of dt from y_ at t: the whole step and two halves, y at the end (the halves') and the error
  // estimate, or nothing with the cause in why.
  struct Try {
    std::optional<Element> y;
    double error = 0.0;
    int order = 0;  // of the estimate: the next step's exponent is -1/(order+1)
    int substeps = 2;
  };
  Try try_step(const StepSizeControl& control, double t, double dt, bool refine, StepRecord& attempt,
               std::string& why) {
    if (stepper_.estimates_error() && stepper_.stiff(y_, t, dt))
      return try_embedded(control, t, dt, refine, attempt, why);
    const auto first = stepper_.take(y_, t, dt / 2, attempt);
    const auto second = first ? stepper_.take(*first, t + dt / 2, dt / 2, attempt) : std::nullopt;
    const auto whole = second ? stepper_.take(y_, t, dt, attempt) : std::nullopt;
    if (!whole) {
      why = "the try at h = " + format_number(dt) + " failed (" + std::string(to_string(attempt.status)) +
            "): " + stepper_.failure();
      return {};
    }
    const double err = control.error(group_.matrix(y_), group_.matrix(*whole), group_.matrix(*second));
    if (!(err <= 1.0)) {
      why = "the error estimate at h = " + format_number(dt) + " is " + format_number(err);
      return {std::nullopt, err, control.order};
    }
    return {second, err, control.order};
  }

  // One step and its embedded estimate; refine: the first try or the one after a rejection, where an estimate
  // above 1 is evaluated again (embedded_estimate.hpp).
  Try try_embedded(const StepSizeControl& control, double t, double dt, bool refine, StepRecord& attempt,
                   std::string& why) {
    const auto next = stepper_.take(y_, t, dt, attempt);
    if (!next) {
      why = "the try at h = " + format_number(dt) + " failed (" + std::string(to_string(attempt.status)) +
            "): " + stepper_.failure();
      return {};
    }
    const auto size = [&](const typename G::Vector& e) {
      const Eigen::MatrixXd y0 = group_.matrix(y_);
      return control.scaled(y0, group_.matrix(*next), group_.matrix(group_.times_exp(y_, e)) - y0);
    };
    double err = size(stepper_.error_estimate(false, attempt));
    if (refine && !(err <= 1.0)) err = size(stepper_.error_estimate(true, attempt));
    if (!(err <= 1.0)) {
      why = "the embedded error estimate at h = " + format_number(dt) + " is " + format_number(err);
      return {std::nullopt, err, stepper_.estimate_order(), 1};
    }
    return {next, err, stepper_.estimate_order(), 1};
  }

  // t to 12 digits: where the steps fell below the minimum step, 3 digits would not tell t from a neighbour.
  static std::string time_text(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.12g", x);
    return std::string(buf);
  }

  // Whether the adaptive run must end before trying dt at t (it then sets the status and reason).
  bool adaptive_run_ends(double t, double dt, int tries, int rejected_now, const std::string& why) {
    if (tries == req_.max_steps) {
      res_.status = Status::max_steps;
      res_.reason = "max_steps = " + std::to_string(req_.max_steps) + " tries (" + std::to_string(res_.steps.size()) +
                    " accepted, " + std::to_string(res_.rejected + rejected_now) + " rejected) reached t = " +
                    time_text(t) + " of t_end = " + format_number(req_.t_end);
      return true;
    }
    if (dt < StepSizeControl::kMinStepFraction * req_.t_end && dt < req_.t_end - t) {
      res_.status = Status::min_step;
      res_.reason = "at t = " + time_text(t) + " the step size fell to " + format_number(dt) +
                    ", below the minimum step " + format_number(StepSizeControl::kMinStepFraction * req_.t_end) +
                    " (1e-10 t_end): " + why;
      return true;
    }
    return false;
  }

  void adaptive_steps() {
    const StepSizeControl control{req_.rtol.value_or(req_.atol.value_or(0.0)),
                                  req_.atol.value_or(req_.rtol.value_or(0.0)), tab_.order};
    double t = 0.0, dt = std::min(*req_.h, req_.t_end);
    double h_smallest = req_.t_end, h_largest = 0.0;
    bool after_rejection = false;
    int tries = 0;
    StepRecord rec;   // the step being tried: the work of its rejected tries counts in it
    std::string why;  // the last rejection's cause
    while (t < req_.t_end) {
      // The last step stretches to t_end rather than leave a sliver behind.
      if (req_.t_end - t <= 1.1 * dt) dt = req_.t_end - t;
      if (adaptive_run_ends(t, dt, tries, rec.rejected, why)) return;
      ++tries;
      StepRecord attempt = rec;
      attempt.status = Status::converged;
      const Try step = try_step(control, t, dt, after_rejection || res_.steps.empty(), attempt, why);
      rec.iterations = attempt.iterations;
      rec.jacobian_evaluations = attempt.jacobian_evaluations;
      rec.factorizations = attempt.factorizations;
      if (!step.y) {
        ++rec.rejected;
        dt *= std::isfinite(step.error) && step.error > 0.0 ? control.factor(step.error, true, step.order)
                                                             : StepSizeControl::kFailureFactor;
        after_rejection = true;
        continue;
      }
      y_ = *step.y;
      const bool last = dt == req_.t_end - t;
      t = last ? req_.t_end : t + dt;
      attempt.step = static_cast<int>(res_.steps.size()) + 1;
      attempt.t = t;
      attempt.h = dt;
      attempt.error_estimate = step.error;
      attempt.substeps = step.substeps;
      h_smallest = std::min(h_smallest, dt);
      h_largest = std::max(h_largest, dt);
      if (!record(attempt, last)) return cancelled_after(attempt.step);
      rec = StepRecord{};
      dt *= control.factor(step.error, after_rejection, step.order);
      after_rejection = false;
    }
    res_.reason = std::to_string(res_.steps.size()) + " adaptive steps (" + std::to_string(res_.rejected) +
                  " tries rejected), h from " + format_number(h_smallest) + " to " + format_number(h_largest) +
                  ", every error estimate <= 1 (rtol " + format_number(control.rtol) + ", atol " +
                  format_number(control.atol) + ")" +
                  (tab_.solves_stages() ? "; every stage converged to the root continued from its start" : "");
  }

  void keep(int k, double t) {
    res_.frames.push_back(group_.matrix(y_));
    res_.frame_times.push_back(t);
    res_.frame_steps.push_back(k);
  }

  void keep_frame(int k, double t, bool last) {
    if (!frame_stride_ || (k % frame_stride_ != 0 && !last)) return;
    keep(k, t);
    if (!res_.adaptive || res_.frames.size() <= 2 * static_cast<std::size_t>(req_.frames) + 1) return;
    frame_stride_ *= 2;
    std::size_t kept = 0;
    for (std::size_t i = 0; i < res_.frames.size(); ++i) {
      if (res_.frame_steps[i] % frame_stride_ != 0 && !(last && i + 1 == res_.frames.size())) continue;
      if (kept != i) res_.frames[kept] = std::move(res_.frames[i]);
      res_.frame_times[kept] = res_.frame_times[i];
      res_.frame_steps[kept++] = res_.frame_steps[i];
    }
    res_.frames.resize(kept);
    res_.frame_times.resize(kept);
    res_.frame_steps.resize(kept);
  }

  // A step's record (y_ is its end state); false when the caller asks to stop.
  bool record(StepRecord& rec, bool last) {
    rec.invariants = invariants(y_);
    drift_.add(rec.invariants);
    res_.orthogonality_error = std::max(res_.orthogonality_error, group_.defect(y_));
    res_.steps.push_back(rec);
    res_.total_iterations += rec.iterations;
    if (rec.jacobian_evaluations) {
      res_.jacobian_evaluations = res_.jacobian_evaluations.value_or(0) + *rec.jacobian_evaluations;
      res_.factorizations = res_.factorizations.value_or(0) + *rec.factorizations;
    }
    res_.substeps += rec.substeps;
    res_.rejected += rec.rejected;
    keep_frame(rec.step, rec.t, last);
    return !on_step_ || on_step_(rec);
  }

  void cancelled_after(int k) {
    res_.status = Status::cancelled;
    res_.reason = "cancelled by the caller after step " + std::to_string(k);
  }

  G group_;
  const IntegrateRequest& req_;
  const StepCallback& on_step_;
  std::unique_ptr<VectorField<G>> field_;
  const Tableau& tab_;
  Stepper<G> stepper_;
  bool conserves_;
  Element y_;
  InvariantDrift drift_;
  IntegrateResult res_;
  int frame_stride_ = 0;
};

}  // namespace integrators

template <LieGroup G>
IntegrateResult integrate_on(const G& group, const IntegrateRequest& req, const Eigen::MatrixXd& y0,
                             const StepCallback& on_step) {
  return integrators::Integration<G>(group, req, y0, on_step).run();
}

}  // namespace lienewton
