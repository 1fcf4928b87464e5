#pragma once
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>

#include "core/cancellation.hpp"
#include "core/reference_solution.hpp"
#include "integrate_on.hpp"

namespace lienewton {

// reference_solution(): RKMK4 at kReferenceStepsPerUnit steps per unit of time or more, the steps doubled until two
// successive finite solutions agree to kReferenceTolerance (RKMK4's error at the finer is about 1/15 of their
// distance: the error it reports): a fast field (the heavy top's spin of 150 rad/s) needs a hundred times the steps a slow one does, a
// stiff one (an eigenvalue -1e4) the steps that bring h |lambda| inside RKMK4's stability interval; its overflowing
// runs are skipped. Past kMaxReferenceSteps, rkmk-radau3 (L-stable) refined the same way from 64 steps.
template <LieGroup G>
ReferenceSolution reference_on(const G& group, const ProblemSpec& problem, const Eigen::MatrixXd& y0, double t_end) {
  const auto field = make_field(group, problem);
  const integrators::Tableau& rkmk4 = integrators::tableau_of(Integrator::rkmk4);
  const auto explicit_run = [&](long long steps) {
    const double h = t_end / static_cast<double>(steps);
    typename G::Element y = group.element(y0);
    for (long long k = 0; k < steps; ++k) {
      throw_if_cancelled();
      y = integrators::explicit_rkmk_step(group, *field, rkmk4, y, static_cast<double>(k) * h, h);
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
  // Doubles the steps of run (a method of order `order`) from `steps` until two finite solutions agree to tolerance
  // relative or max is reached.
  const auto refine = [&](const auto& run, int order, long long steps, long long max, double tolerance,
                          const char* name) -> ReferenceSolution {
    Eigen::MatrixXd coarse = run(steps);
    while (steps < max) {
      steps *= 2;
      Eigen::MatrixXd fine = run(steps);
      if (fine.allFinite() && coarse.allFinite()) {
        const double distance = (fine - coarse).norm();
        if (distance <= tolerance * std::max(1.0, fine.norm()))
          return {std::move(fine), distance / static_cast<double>((1 << order) - 1),
                  std::string(name) + " at " + std::to_string(steps) + " steps"};
      }
      coarse = std::move(fine);
    }
    return {};
  };
  // The first comparison is against half the steps, so a slow field costs 1.5 times one run at
  // kReferenceStepsPerUnit, whose solution it returns.
  const long long first = std::max(32LL, static_cast<long long>(std::ceil(t_end * kReferenceStepsPerUnit / 2)));
  if (ReferenceSolution r = refine(explicit_run, 4, first, kMaxReferenceSteps, kReferenceTolerance, "rkmk4"); r.y)
    return r;
  if (ReferenceSolution r = refine(implicit_run, 3, 64, kMaxImplicitReferenceSteps, kImplicitReferenceTolerance,
                                   "rkmk-radau3");
      r.y)
    return r;
  return {.note = "no reference solution: rkmk4 up to " + std::to_string(kMaxReferenceSteps) +
                  " steps and rkmk-radau3 up to " + std::to_string(kMaxImplicitReferenceSteps) +
                  " steps did not settle (two refinements agreeing to " + format_number(kImplicitReferenceTolerance) +
                  ")"};
}

}  // namespace lienewton
