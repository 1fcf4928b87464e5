#pragma once
// One step of an integrator from y at time t, of any form and any number of stages (tableau.hpp). A DIRK method
// solves every stage equation by the request's method (section 6) at the root continued from its Z_i
// (continuation.hpp: the path from h = 0 of the stage, which starts at the explicit Lie-Euler value
// Z_i exp(h a_ii g(Z_i)), the tangent's prediction, unless the predictor is none). An implicit RKMK method solves its
// coupled stage system at the root continued from h = 0 (rkmk_stages.hpp), from the stages extrapolated from the
// previous step (lie-euler; none: from K = 0), and gives the embedded error estimate of its step
// (embedded_estimate.hpp). With the simplified Newton (dexpinv-0) its decoupled matrix (stage_decoupling.hpp) is
// kept across steps: J = dg_{y_k} is evaluated again only after a solve that contracted slowly (rate above
// kReuseContraction) or failed with the kept one, and the blocks factored again when J or h changed (Hairer &
// Wanner II, section IV.8). An explicit RKMK method only evaluates.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/cancellation.hpp"
#include "core/integrate.hpp"
#include "core/problems.hpp"
#include "core/solvers/continuation.hpp"
#include "core/solvers/spectrum.hpp"
#include "core/solvers/run_method.hpp"
#include "embedded_estimate.hpp"
#include "rkmk_stages.hpp"
#include "stage_decoupling.hpp"
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
      : group_(group), field_(&field), tab_(&tab), opt_(opt), predictor_(predictor) {
    opt_.stop_at_rounding = true;  // a stage at rounding is solved (SolverOptions::stop_at_rounding)
    if (tab.form == Form::implicit_rkmk) {
      matrix_.emplace(tab);
      weights_ = embedded_weights(tab, matrix_->decoupling().gamma0);
    }
  }

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
  // How the largest Newton systems solved so far were factored (none before any was).
  std::optional<Factorization> factorization() const { return factorization_; }

  // Whether a step of dt from y at t is stiff: a component of the linearisation decays within it, h (-Re mu) > 1
  // for an eigenvalue mu of dg_y. Step doubling's estimate then misjudges (order reduction) and the embedded one is
  // filtered for it; a fast rotation (the heavy top's spin, Re mu ~ 0) is not stiff. dg_y and its eigenvalues are
  // kept for the tries from the same (t, y). A system above a dense LU's size is stiff where h ||dg_y||_F > 1: its
  // eigenvalues would cost O(q^3) at every step, more than the step, and the filtered embedded estimate holds in
  // either regime (at a third of step doubling's steps).
  bool stiff(const Element& y, double t, double dt) {
    if (!start_ || start_->t != t || start_->y != y) {
      field_->set_time(t);
      start_.emplace(StartJacobian{t, y, DynamicOperator<G>(field_->dg_matrix(group_, y)), {}});
    }
    StartJacobian& s = *start_;
    if (!(dt * s.j.norm() > 1.0)) return false;  // |Re mu| <= ||dg_y||_F
    if (kSparseOperator<G> && s.j.rows() > dense_lu_max_dim()) return true;
    if (!s.spectrum) s.spectrum.emplace(Eigen::MatrixXd(s.j));
    return s.spectrum->decays_faster_than(1.0 / dt);
  }
  // Whether take() can give an embedded error estimate (implicit RKMK methods), and its order s.
  bool estimates_error() const { return weights_.has_value(); }
  int estimate_order() const { return weights_ ? weights_->order : 0; }
  // The last successful implicit RKMK step's embedded error estimate err, in the algebra at its start y_k; refined:
  // with g evaluated again at y_k exp(err) (rec counts the matrices the filter needs).
  Vector error_estimate(bool refined, StepRecord& rec) {
    prepare_filter(last_.y, last_.t, last_.h, rec);
    const Vector err = filtered(last_.g, last_.h);
    if (!refined) return err;
    field_->set_time(last_.t);
    return filtered(field_->g(group_.times_exp(last_.y, err)), last_.h);
  }

 private:
  std::optional<Element> explicit_step(const Element& y, double t, double dt, StepRecord& rec) {
    rec.add_matrices(0, 0);
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
      const SolveResult stage = continued_root(opt_.method, eq, opt_, {},
                                               predictor_ == Predictor::none ? FirstTry::z
                                                                             : FirstTry::tangent_then_linear);
      rec.iterations += stage.total_iterations();
      if (opt_.method != Method::fixed_point) used(stage.linear_solver);
      rec.residual = std::max(rec.residual, stage.residual);
      // A stage at its rounding floor (stagnated: tol is below what double resolves at this h, as on a stiff
      // field) is solved as well as it can be; so is an implicit RKMK stage (rkmk_stages.hpp).
      if (!is_root(stage) || stage.branch != Branch::continued) {
        rec.status = is_root(stage) ? Status::fold : stage.status;
        failure_ = "stage " + std::to_string(i + 1) + " (h = " + format_number(dt) + "): " + stage.reason;
        return std::nullopt;
      }
      last_stage = Element(stage.y);
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
    const bool simplified = opt_.method != Method::fixed_point && opt_.differential == Differential::dexpinv_0;
    if (simplified) prepare_matrix(y, t, dt, rec);
    StageSolution stages = continued_stages(sys, start, opt_.method, opt_.differential, opt_,
                                            simplified ? &*matrix_ : nullptr, tangent_guides_);
    // The kept J may be what failed: once more with dg_{y_k}.
    if (simplified && !stages.continued && !jacobian_fresh_) {
      rec.iterations += stages.iterations;
      rec.add_matrices(stages.jacobian_evaluations, stages.factorizations);
      refresh_matrix(y, t, dt, rec);
      stages = continued_stages(sys, start, opt_.method, opt_.differential, opt_, &*matrix_, tangent_guides_);
    }
    rec.iterations += stages.iterations;
    rec.add_matrices(stages.jacobian_evaluations, stages.factorizations);
    if (stages.factorization) used(*stages.factorization);
    rec.residual = std::max(rec.residual, stages.residual());
    reuse_jacobian_ = simplified && stages.continued && stages.contraction <= kReuseContraction;
    if (!stages.continued) {
      rec.status = stages.status == Status::converged ? Status::fold : stages.status;
      failure_ = "stages (h = " + format_number(dt) + "): " + stages.reason;
      return std::nullopt;
    }
    previous_.emplace(t, g);
    tangent_guides_ = stages.near_tangent;
    if (weights_) last_ = {y, t, dt, stage_sum(sys.thetas(stages.k)), g, false};
    return sys.next(stages.k);
  }

  // Simplified Newton: J = dg_{y_k} at this step unless the last one may be kept; the blocks for dt.
  void prepare_matrix(const Element& y, double t, double dt, StepRecord& rec) {
    if (!jacobian_ || !reuse_jacobian_) return refresh_matrix(y, t, dt, rec);
    jacobian_fresh_ = false;
    if (matrix_->h() != dt) factorize(dt, rec);
  }
  void refresh_matrix(const Element& y, double t, double dt, StepRecord& rec) {
    field_->set_time(t);
    jacobian_ = DynamicOperator<G>(field_->dg_matrix(group_, y));
    rec.add_matrices(1, 0);
    jacobian_fresh_ = true;
    factorize(dt, rec);
  }
  void factorize(double dt, StepRecord& rec) {
    matrix_->factorize(dt, *jacobian_);
    rec.add_matrices(0, 1);
    used(matrix_->factorization());
  }
  void used(Factorization f) { factorization_ = widest(factorization_, f); }
  // The estimate's filter (I - h gamma0 J)^-1 with J = dg at this step's start, unless the simplified Newton's kept
  // one is already factored at dt (any J near dg_{y_k} filters; Radau5 uses its Newton matrix's).
  void prepare_filter(const Element& y, double t, double dt, StepRecord& rec) {
    const bool kept = opt_.differential == Differential::dexpinv_0 && opt_.method != Method::fixed_point &&
                      jacobian_ && matrix_->h() == dt;
    if (!kept && !last_.filter_ready) refresh_matrix(y, t, dt, rec);
    last_.filter_ready = true;
  }

  // sum_j e_j Theta_j of the stacked stages Theta.
  Vector stage_sum(const Eigen::VectorXd& thetas) const {
    const int q = group_.dim();
    Vector sum = zero_vector(group_);
    for (int j = 0; j < tab_->stages(); ++j) sum += weights_->e(j) * Vector(thetas.segment(j * q, q));
    return sum;
  }
  // err = (I - h gamma0 J)^-1 (h gamma0 g + sum_j e_j Theta_j).
  Vector filtered(const Vector& g, double dt) const {
    return Vector(matrix_->filter(Eigen::VectorXd((dt * weights_->gamma0) * g + last_.stages)));
  }

  // J is evaluated again after a solve whose corrections shrank by less than this factor each.
  static constexpr double kReuseContraction = 0.1;
  G group_;
  VectorField<G>* field_;
  const Tableau* tab_;
  SolverOptions opt_;
  Predictor predictor_;
  // The last start (t, g(t, y)) of a solved RKMK step: the predictor extrapolates g linearly from it (a secant
  // through a later point too: adaptive steps take the whole step after its two halves).
  std::optional<std::pair<double, Vector>> previous_;
  // The last solved step's root passed the tangent's test: a stiff step then tries the predicted stages first
  // (continued_stages' start_first), which saves the iteration that only reaches the linearly implicit stages.
  bool tangent_guides_ = false;
  std::string failure_;
  std::optional<Factorization> factorization_;
  // Implicit RKMK methods: the decoupled Newton matrix (also the estimate's filter), its J and whether it may be
  // kept, and the embedded estimate's weights and last step.
  std::optional<DecoupledNewtonMatrix> matrix_;
  std::optional<DynamicOperator<G>> jacobian_;
  bool jacobian_fresh_ = false, reuse_jacobian_ = false;
  std::optional<EmbeddedWeights> weights_;
  struct StartJacobian {  // stiff()'s dg_y at (t, y), and its eigenvalues once they were needed
    double t;
    Element y;
    DynamicOperator<G> j;
    std::optional<Spectrum> spectrum;
  };
  std::optional<StartJacobian> start_;
  struct LastStep {
    Element y;
    double t = 0, h = 0;
    Vector stages;  // sum_j e_j Theta_j
    Vector g;       // g(t_k, y_k)
    bool filter_ready = false;  // the filter is factored for this step
  } last_;
};

}  // namespace lienewton::integrators
