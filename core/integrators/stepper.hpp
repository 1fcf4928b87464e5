#pragma once
// One step of an integrator from y at time t, of any form and any number of stages (tableau.hpp). A DIRK method
// solves every stage equation by the request's method (section 6) at the root continued from its Z_i
// (continuation.hpp: the path from h = 0 of the stage, which starts at the explicit Lie-Euler value
// Z_i exp(h a_ii g(Z_i)), the tangent's prediction, unless the predictor is none). An implicit RKMK method solves its
// coupled stage system at the root continued from h = 0 (rkmk_stages.hpp), from the stages extrapolated from the
// previous step (lie-euler; none: from K = 0). An explicit RKMK method only evaluates.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/cancellation.hpp"
#include "core/integrate.hpp"
#include "core/problems.hpp"
#include "core/solvers/continuation.hpp"
#include "rkmk_stages.hpp"
#include "tableau.hpp"

namespace lienewton::integrators {

// An explicit RKMK step (Form::explicit_rkmk): k_i = h dexpinv_{Theta_i}(g(t + c_i h, y exp Theta_i)) with the
// exact dexpinv (3.9); a stage with Theta_i = 0 is g at y itself.
template <LieGroup G>
typename G::Element explicit_rkmk_step(const G& group, VectorField<G>& field, const Tableau& tab,
                                       const typename G::Element& y, double t, double h) {
  using Vector = typename G::Vector;
  std::vector<Vector> k;
  Vector u = zero_vector(group);
  for (int i = 0; i < tab.stages(); ++i) {
    Vector theta = zero_vector(group);
    bool at_y = true;
    for (int j = 0; j < i; ++j) {
      if (tab.a(i, j) == 0.0) continue;
      theta += tab.a(i, j) * k[static_cast<std::size_t>(j)];
      at_y = false;
    }
    field.set_time(t + tab.c(i) * h);
    k.push_back(at_y ? Vector(h * field.g(y))
                     : Vector(h * group.dexpinv(group.spectral(theta), field.g(group.times_exp(y, theta)))));
    u += tab.b(i) * k.back();
  }
  return group.times_exp(y, u);
}

template <LieGroup G>
class Stepper {
 public:
  using Element = typename G::Element;
  using Vector = typename G::Vector;

  Stepper(const G& group, VectorField<G>& field, const Tableau& tab, const SolverOptions& opt, Predictor predictor)
      : group_(group), field_(&field), tab_(&tab), opt_(opt), predictor_(predictor) {}

  // y at t + dt, or nothing with rec's status and failure() set by the failing stage; rec sums the stages' work.
  std::optional<Element> take(const Element& y, double t, double dt, StepRecord& rec) {
    throw_if_cancelled();
    switch (tab_->form) {
      case Form::implicit_rkmk: return rkmk_step(y, t, dt, rec);
      case Form::dirk_crouch_grossman: return dirk_step(y, t, dt, rec);
      case Form::explicit_rkmk: break;
    }
    return explicit_step(y, t, dt, rec);
  }
  // What the last failing step ran into.
  const std::string& failure() const { return failure_; }

 private:
  std::optional<Element> explicit_step(const Element& y, double t, double dt, StepRecord& rec) {
    Element next = explicit_rkmk_step(group_, *field_, *tab_, y, t, dt);
    if (group_.matrix(next).allFinite()) return next;
    rec.status = Status::non_finite;
    failure_ = "the explicit step (h = " + format_number(dt) + ") is not finite";
    return std::nullopt;
  }

  std::optional<Element> dirk_step(const Element& y, double t, double dt, StepRecord& rec) {
    std::vector<Vector> hg;  // h g(Y_j) of the stages solved so far
    Element last_stage;
    for (int i = 0; i < tab_->stages(); ++i) {
      field_->set_time(t + tab_->c(i) * dt);
      Element z = y;
      for (int j = 0; j < i; ++j) z = group_.times_exp(z, tab_->a(i, j) * hg[static_cast<std::size_t>(j)]);
      const auto eq = Equation<G>::implicit_euler(group_, z, dt * tab_->a(i, i), *field_);
      const SolveResult stage = continued_root(opt_.method, eq, opt_, {}, predictor_ == Predictor::none);
      rec.iterations += stage.total_iterations();
      rec.residual = std::max(rec.residual, stage.residual);
      if (stage.status != Status::converged || stage.branch != Branch::continued) {
        rec.status = stage.status == Status::converged ? Status::fold : stage.status;
        failure_ = "stage " + std::to_string(i + 1) + " (h = " + format_number(dt) + "): " + stage.reason;
        return std::nullopt;
      }
      last_stage = group_.element(stage.y);
      hg.push_back(dt * field_->g(last_stage));
    }
    // A stiffly accurate tableau's exp-products of the b_i are Y_s: taking Y_s saves s products and their
    // rounding (orthogonality drift over 1e4 steps drops ~10x).
    if (tab_->stiffly_accurate()) return last_stage;
    Element next = y;
    for (int i = 0; i < tab_->stages(); ++i) next = group_.times_exp(next, tab_->b(i) * hg[static_cast<std::size_t>(i)]);
    return next;
  }

  std::optional<Element> rkmk_step(const Element& y, double t, double dt, StepRecord& rec) {
    const RkmkStages<G> sys(group_, *field_, *tab_, y, t, dt);
    const Vector g = sys.g_at_start();
    Eigen::VectorXd start = Eigen::VectorXd::Zero(sys.size());
    if (predictor_ != Predictor::none)
      start = previous_ && previous_->first != t
                  ? sys.along(g, Vector((g - previous_->second) / (t - previous_->first)))
                  : sys.constant(g);
    const StageSolution stages = continued_stages(sys, start, opt_.method, opt_.differential, opt_);
    rec.iterations += stages.iterations;
    rec.residual = std::max(rec.residual, stages.residual());
    if (!stages.continued) {
      rec.status = stages.status == Status::converged ? Status::fold : stages.status;
      failure_ = "stages (h = " + format_number(dt) + "): " + stages.reason;
      return std::nullopt;
    }
    previous_.emplace(t, g);
    return sys.next(stages.k);
  }

  G group_;
  VectorField<G>* field_;
  const Tableau* tab_;
  SolverOptions opt_;
  Predictor predictor_;
  // The last start (t, g(t, y)) of a solved RKMK step: the predictor extrapolates g linearly from it (a secant
  // through a later point too: adaptive steps take the whole step after its two halves).
  std::optional<std::pair<double, Vector>> previous_;
  std::string failure_;
};

}  // namespace lienewton::integrators
