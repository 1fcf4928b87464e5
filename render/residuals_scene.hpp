#pragma once
// Solver speed against accuracy: ||f(y_n)|| against the solver's cumulative CPU time for every
// (method, differential) of one equation, beside ||f(y_n)|| against the iteration n. A finite-difference
// Newton and an exact one may share the right panel's curve yet lie far apart in the left one.
#include <string>
#include <vector>

#include "core/options.hpp"
#include "core/status.hpp"
#include "render/figure.hpp"

namespace lienewton::render {

// One solve's trace: per iterate n = 0, 1, ..., the solver CPU time so far and the residual.
struct ResidualRun {
  Method method = Method::newton_group;
  Differential differential = Differential::exact;
  Status status = Status::converged;
  std::vector<double> cpu_seconds;
  std::vector<double> residual;
};

// Runs are styled by position (series_style). Iterates whose residual or time is not positive are left out
// of the log axes. The legend gives each run's iterations and its CPU time to the last iterate ("time to
// tol" when it converged). Throws std::invalid_argument when no point is left or the lengths differ.
Figure residuals_scene(const std::vector<ResidualRun>& runs, const std::string& title, int width, int height);

}  // namespace lienewton::render
