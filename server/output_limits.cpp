#include "server/output_limits.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/group_registry.hpp"
#include "server/http_errors.hpp"

namespace lienewton::service {
namespace {

// Values per step record and per sweep cell in the JSON result, counted on a serialised one: a field added to
// the record is counted without an edit here.
double step_values() {
  static const double values = static_cast<double>(to_json(StepRecord{}).size());
  return values;
}
double cell_values() {
  static const double values = static_cast<double>(to_json(SweepCell{}).size());
  return values;
}

void refuse_beyond(double values, const OutputLimits& limits, const char* field, const std::string& what) {
  if (values <= static_cast<double>(limits.max_values)) return;
  throw ApiError(413, "output_too_large", field,
                 what + " would return " + std::to_string(static_cast<long long>(values)) +
                     " numbers, more than the server's limit of " + std::to_string(limits.max_values));
}

// Numbers in one state y: its matrix's (n x n on SO(n), 4 x 4 on SE(3), 11 x 11k on k bodies (SE(3) x R^6)^k).
double state_values(const ProblemSpec& problem) {
  const MatrixShape shape = problem.family().matrix_shape(problem.n);
  return double(shape.rows) * double(shape.cols);
}

// Step records an integration can return: adaptive, at most max_steps; fixed, t_end / h rounded, as the
// integrator takes them (at least one).
double planned_steps(const IntegrateRequest& r) {
  return r.adaptive() ? r.max_steps : std::max(1.0, std::round(r.t_end / *r.h));
}

// States an integration's answer holds with f frames: y, and its frames. Fixed steps keep y(0), every
// max(1, floor(S / f))-th step and the last; adaptive ones are thinned to at most 2f + 1.
double planned_states(const IntegrateRequest& r, int frames) {
  if (frames == 0) return 1;
  if (r.adaptive()) return 2.0 * frames + 2.0;
  const double steps = planned_steps(r), stride = std::max(1.0, std::floor(steps / frames));
  const double strided = std::floor(steps / stride) + 1, last = std::fmod(steps, stride) != 0 ? 1 : 0;
  return strided + last + 1;
}

double planned_values(const IntegrateRequest& r, int frames) {
  return planned_steps(r) * step_values() + planned_states(r, frames) * state_values(r.problem);
}

}  // namespace

void check_output(const SolveRequest& r, const OutputLimits& limits) {
  if (!r.solver.include_iterates) return;
  const int n = r.problem.n, max_iterations = r.solver.max_iterations;
  const double values = (max_iterations + 1.0) * state_values(r.problem);
  refuse_beyond(values, limits, "include_iterates", "include_iterates with max_iterations " +
                                                         std::to_string(max_iterations) + " and n " + std::to_string(n));
}

void check_output(const IntegrateRequest& r, const OutputLimits& limits) {
  refuse_beyond(planned_values(r, r.frames), limits, r.frames > 0 ? "frames" : "h", "this integration");
}

void fit_output(IntegrateRequest& r, const OutputLimits& limits) {
  if (!r.adaptive()) return;
  const double states = planned_states(r, r.frames) * state_values(r.problem);
  const double room = std::floor((static_cast<double>(limits.max_values) - states) / step_values());
  if (room >= 1 && room < r.max_steps) r.max_steps = static_cast<int>(room);
}

int fitting_frames(const IntegrateRequest& r, int wanted, const OutputLimits& limits) {
  const double cap = static_cast<double>(limits.max_values);
  int frames = wanted;  // at most kMaxFrames tries: the count is not monotone in f where the stride changes
  while (frames > r.frames && planned_values(r, frames) > cap) --frames;
  return std::max(r.frames, frames);
}

void check_output(const SweepRequest& r, const OutputLimits& limits) {
  const double cells = static_cast<double>(r.methods.size()) * static_cast<double>(r.n.size()) * static_cast<double>(r.h.size());
  refuse_beyond(cells * cell_values(), limits, "h", "this sweep grid");
}

void check_output(const BasinRequest& r, const OutputLimits& limits) {
  const double pixels = static_cast<double>(r.size) * r.size * static_cast<double>(r.methods.size());
  refuse_beyond(pixels * kBasinPixelValues, limits, "size", "a " + std::to_string(r.size) + " x " + std::to_string(r.size) +
                                                          " basin map of " + std::to_string(r.methods.size()) + " methods");
}

void check_image_pixels(const json& body, const OutputLimits& limits) {
  if (!body.is_object()) return;
  auto size = [&](const char* field) -> double {
    const auto it = body.find(field);
    return it != body.end() && it->is_number_integer() ? it->get<double>() : 0.0;
  };
  const double pixels = size("width") * size("height");
  if (pixels <= static_cast<double>(limits.max_image_pixels)) return;
  throw ApiError(413, "output_too_large", "width",
                 "width x height = " + std::to_string(static_cast<long long>(pixels)) +
                     " pixels, more than the server's limit of " + std::to_string(limits.max_image_pixels));
}

void apply_output_limits(PreparedRequest& request, const OutputLimits& limits) {
  std::visit([&](auto& r) { apply_output_limits(r, limits); }, request.request_);
}

}  // namespace lienewton::service
