#pragma once
// Time stepping of y' = y g(y) on [0, t_end] with implicit Lie group integrators whose stages are solved by
// any solver/differential, compared against a reference solution.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "fields.hpp"
#include "invariants.hpp"
#include "problem_spec.hpp"
#include "solver_options.hpp"
#include "status.hpp"

namespace lienewton {

struct IntegrateRequest {
  ProblemSpec problem{.kind = ProblemKind::rigid_body};  // z is y(0)
  SolverOptions solver{};  // for every stage equation (include_iterates is not used)
  // The step (adaptive steps: the first one tried). Absent: default_step() of the problem's time scale, resolved by
  // resolve_defaults() before anything runs.
  std::optional<double> h{};
  double t_end = 1.0;
  // Two-stage Gauss (order 4, A-stable, symplectic): at the default step every built-in problem's answer is within
  // 1e-3 of its reference (the heavy top 4e-4 of a norm of 150, where implicit Euler's damped path is 6.9 off) for
  // about the cost of implicit Euler (1.0-1.6x). Where a request leaves it out and its coupled stage system is too
  // large to solve densely, resolve_defaults() takes dirk-cg3 instead (integrator_defaulted).
  Integrator integrator = Integrator::rkmk_gauss2;
  // Where each stage's first solve starts: lie-euler (default) at the explicit Lie-Euler value, the tangent of the
  // stage's branch of roots at h = 0; none at Z_i, as the paper starts at y_0 = z. Either way the stage's root must
  // be the one continued from Z_i (core/integrators/stepper.hpp).
  Predictor predictor = Predictor::lie_euler;
  int frames = 0;                     // number of evenly spaced states y(t_k) to return (0: none), at most kMaxFrames
  static constexpr int kMaxFrames = 1000;
  bool reference = true;              // compute the reference solution and the global error
  // Adaptive steps (step doubling, docs/integrators.md): with rtol or atol (the other then takes the same value)
  // the integrator chooses its step sizes, h is the first step tried, and at most max_steps steps (accepted and
  // rejected) are taken.
  std::optional<double> rtol{}, atol{};
  int max_steps = static_cast<int>(fields::max_steps.default_value);
  bool h_defaulted = false;  // not a field: h is resolve_defaults()'s, from the problem's time scale
  bool integrator_defaulted = false;  // not a field: the request did not name one (the codec sets it)
  bool adaptive() const { return rtol || atol; }
};

// What a converged integration's answer warns of: its stages converged, yet the trajectory may not be the solution's.
// code names the kind (IntegrateWarning's codes in words(), the OpenAPI schema); message says it with the numbers.
struct IntegrateWarning {
  std::string code;
  std::string message;
};
// Work-precision's fits stop at errors above this fraction of ||y_ref(t_end)||_F: not small against the solution.
inline constexpr double kSolutionScaleFraction = 5e-2;
// The thresholds of integrate's warnings: a global error above this fraction of ||y_ref(t_end)||_F is inaccurate
// (the state's norm mixes a body's rotation with its rates: on the heavy top ||y|| ~ 150 is its spin, so a rotation
// 88 degrees off is 4.5 % of it); an invariant drifting by more than this fraction of its scale is not conserved; a
// default step more than this many times the field's time scale 1/rho (time_scale.hpp) was raised past it to fit the
// step budget.
inline constexpr double kInaccurateFraction = 1e-2;
inline constexpr double kInvariantDriftWarning = 1e-2;
inline constexpr double kDefaultStepOverTimeScale = 2.0;
// The codes, one per threshold above, in that order.
inline constexpr const char* kStepEnlarged = "step_enlarged";
inline constexpr const char* kInaccurate = "inaccurate";
inline constexpr const char* kInvariantDrift = "invariant_drift";

struct StepRecord {
  int step = 0;          // 1-based
  double t = 0;          // time at the end of the step
  int iterations = 0;    // summed over stages
  double residual = 0;   // largest final stage residual
  Status status = Status::converged;  // worst stage status
  InvariantValues invariants{};  // the problem's invariants at the state after the step (invariants.hpp)
  int substeps = 0;      // steps taken inside this output step: 1, or more where halving kept the solution's branch
                         // (adaptive: 2, the half steps whose product is y)
  double h = 0;          // the step's size (fixed steps: t_end / steps; adaptive: the accepted step)
  std::optional<double> error_estimate{};  // adaptive: the accepted step's scaled local error estimate (<= 1)
  int rejected = 0;      // adaptive: tries rejected before this step was accepted (error above 1 or a failing stage)
  // RKMK methods: Newton matrices formed (Jacobians dg, or the stage system's) and LU factorizations made in this
  // step, its rejected tries included; the simplified Newton (dexpinv-0) keeps both across steps. Not counted (absent)
  // for DIRK methods, whose stages the equation solvers solve.
  std::optional<int> jacobian_evaluations{};
  std::optional<int> factorizations{};
  void add_matrices(int jacobians, int lus) {
    jacobian_evaluations = jacobian_evaluations.value_or(0) + jacobians;
    factorizations = factorizations.value_or(0) + lus;
  }
};

struct IntegrateResult {
  Status status = Status::converged;  // converged if every stage converged
  std::string reason;
  std::vector<StepRecord> steps;
  std::optional<double> global_error;  // ||y_N - y_ref(t_end)||_F, when reference was requested
  std::optional<double> reference_error;  // y_ref(t_end)'s estimated error (ReferenceSolution::error)
  // global_error is within kReferenceErrorFactor of reference_error: it measures the reference as much as the run.
  bool global_error_at_reference = false;
  InvariantValues initial_invariants{};  // the problem's invariants at y(0)
  InvariantValues invariant_scales{};    // what each drift is relative to (invariant_scales)
  InvariantValues invariant_drifts{};    // max_k |I_k - I_0| / scale over the steps taken (InvariantDrift)
  double orthogonality_error = 0;      // max over steps of ||y^T y - I||_F
  int total_iterations = 0;            // Newton (or fixed-point) iterations summed over every stage of every step
  int substeps = 0;                    // steps taken, halved ones counted as theirs
  double mean_iterations = 0;          // total_iterations / steps taken
  std::optional<int> jacobian_evaluations{};  // summed over the steps where counted (StepRecord)
  std::optional<int> factorizations{};
  // How the Newton systems were factored (the larger kind where a run used two); none for explicit methods and the
  // fixed point, which solve no linear system.
  std::optional<Factorization> linear_solver{};
  Eigen::MatrixXd y;                   // final state
  std::vector<Eigen::MatrixXd> frames; // states at evenly spaced steps when frames > 0 (incl. y(0))
  std::vector<double> frame_times;
  std::vector<int> frame_steps;        // the step k of each frame (0 for y(0)): every max(1, floor(S / frames))-th
                                       // of the S steps and the last one taken
  double cpu_seconds = 0;              // CPU time of the stepping (excluding the reference)
  double reference_seconds = 0;
  bool adaptive = false;               // the steps were chosen by the error estimate (rtol/atol)
  int rejected = 0;                    // adaptive: tries rejected, summed over the steps
  double h = 0;                        // the request's step, or its default (adaptive: the first step tried)
  std::vector<IntegrateWarning> warnings;  // see IntegrateWarning
};

using StepCallback = std::function<bool(const StepRecord&)>;
void validate(const IntegrateRequest& request);
// Gives an absent h its default from the problem's time scale (the problem is validated first: its field is read).
void resolve_defaults(IntegrateRequest& request);
IntegrateResult integrate(const IntegrateRequest& request, const StepCallback& on_step = {});
// integrate() of a request the caller has resolved (resolve_defaults) and validated: it is not checked again.
IntegrateResult integrate_validated(const IntegrateRequest& request, const StepCallback& on_step = {});

}  // namespace lienewton
