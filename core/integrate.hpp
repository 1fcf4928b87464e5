#pragma once
// Time stepping of y' = y g(y) on [0, t_end] with implicit Lie group integrators whose stages are solved by
// any solver/differential, compared against a reference solution.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "problem_spec.hpp"
#include "solver_options.hpp"
#include "status.hpp"

namespace lienewton {

struct IntegrateRequest {
  ProblemSpec problem{.kind = ProblemKind::rigid_body};  // z is y(0)
  SolverOptions solver{};  // for every stage equation (include_iterates is not used)
  double h = 0.1;
  double t_end = 1.0;
  Integrator integrator = Integrator::implicit_euler;
  // Where each stage's iteration starts. lie-euler by default: it costs one g and one exp per stage, never starts
  // worse than Z_i (it falls back to Z_i when its residual is not smaller), and keeps Newton in the basin of the
  // root near y_k (paper-sine N = 5, h = 1/16 converges to a distant root from Z_i = y_k).
  Predictor predictor = Predictor::lie_euler;
  int frames = 0;                     // number of evenly spaced states y(t_k) to return (0: none)
  bool reference = true;              // compute the reference solution and the global error
};

struct StepRecord {
  int step = 0;          // 1-based
  double t = 0;          // time at the end of the step
  int iterations = 0;    // summed over stages
  double residual = 0;   // largest final stage residual
  Status status = Status::converged;  // worst stage status
  double energy = 0;     // rigid body kinetic energy after the step (0 for other problems)
};

struct IntegrateResult {
  Status status = Status::converged;  // converged if every stage converged
  std::string reason;
  std::vector<StepRecord> steps;
  std::optional<double> global_error;  // ||y_N - y_ref(t_end)||_F, when reference was requested
  std::optional<double> energy_drift;  // rigid body: max_k |E_k - E_0| / E_0
  std::optional<double> initial_energy;  // rigid body: E_0 = E(y(0))
  double orthogonality_error = 0;      // max over steps of ||y^T y - I||_F
  int total_iterations = 0;            // Newton (or fixed-point) iterations summed over every stage of every step
  double mean_iterations = 0;          // total_iterations / steps taken
  Eigen::MatrixXd y;                   // final state
  std::vector<Eigen::MatrixXd> frames; // states at evenly spaced steps when frames > 0 (incl. y(0))
  std::vector<double> frame_times;
  std::vector<int> frame_steps;        // the step k of each frame (0 for y(0)): every max(1, floor(S / frames))-th
                                       // of the S steps and the last one taken
  double cpu_seconds = 0;              // CPU time of the stepping (excluding the reference)
  double reference_seconds = 0;
};

using StepCallback = std::function<bool(const StepRecord&)>;
void validate(const IntegrateRequest& request);
IntegrateResult integrate(const IntegrateRequest& request, const StepCallback& on_step = {});

}  // namespace lienewton
