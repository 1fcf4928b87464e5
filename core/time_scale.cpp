#include "time_scale.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "chain.hpp"
#include "group_registry.hpp"

namespace lienewton {

double field_rate(const ProblemSpec& problem) {
  // The chain's own scales instead: its dg's norm mixes k_s / m (1/s^2) with rates (1/s), ~300 times its modes'.
  if (problem.is(ProblemKind::chain)) return Chain{problem.chain}.rate();
  return problem.family().field_rate(problem, problem.start());
}

std::vector<double> default_step_sizes(const ProblemSpec& problem, double t_end) {
  const double rate = field_rate(problem);
  // A field that does not move (rate 0) or overflows at its start has no scale: the slow problems' steps.
  int e = std::ilogb(kMaxDefaultStep);
  if (std::isfinite(rate) && rate > 0.0) e = std::min(e, static_cast<int>(std::floor(-std::log2(rate))));
  // The finest of the kMinDefaultStepCount steps within one integration's limit.
  e = std::max(e, static_cast<int>(std::ceil(std::log2(t_end / kMaxRunSteps))) + kMinDefaultStepCount - 1);
  e = std::max(e, std::numeric_limits<double>::min_exponent + kDefaultStepCount);
  std::vector<double> h;
  for (int k = 0; k < kDefaultStepCount; ++k) {
    const double step = std::ldexp(1.0, e - k);
    if (k >= kMinDefaultStepCount && t_end / step > kMaxDefaultRunSteps) break;
    h.push_back(step);
  }
  return h;
}

double default_step(const ProblemSpec& problem, double t_end, double max_steps) {
  const double h = std::min(kDefaultIntegrationStep, default_step_sizes(problem, t_end).front());
  return std::min(t_end, std::max(h, t_end / max_steps));
}

}  // namespace lienewton
