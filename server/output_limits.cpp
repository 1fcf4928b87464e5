#include "server/output_limits.hpp"

#include <cmath>
#include <string>

#include "core/group_registry.hpp"
#include "server/http_errors.hpp"

namespace lienewton::service {
namespace {

// Values per step record and per sweep cell in the JSON result (step, t, iterations, residual, status,
// energy, substeps, h, error_estimate, rejected; method, n, h, status, reason, iterations, rate, residual, seconds).
constexpr double kStepValues = 10;
constexpr double kCellValues = 9;

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

}  // namespace

void check_output(const SolveRequest& r, const OutputLimits& limits) {
  if (!r.solver.include_iterates) return;
  const int n = r.problem.n, max_iterations = r.solver.max_iterations;
  const double values = (max_iterations + 1.0) * state_values(r.problem);
  refuse_beyond(values, limits, "include_iterates", "include_iterates with max_iterations " +
                                                         std::to_string(max_iterations) + " and n " + std::to_string(n));
}

void check_output(const IntegrateRequest& r, const OutputLimits& limits) {
  // Adaptive: at most max_steps records; frames: at most 2 frames + 1 states besides y(0).
  const double steps = r.adaptive() ? r.max_steps : std::ceil(r.t_end / *r.h);
  const double states = r.adaptive() ? 2.0 * r.frames + 2.0 : r.frames + 1.0;
  const double values = steps * kStepValues + states * state_values(r.problem);
  refuse_beyond(values, limits, r.frames > 0 ? "frames" : "h", "this integration");
}

void fit_output(IntegrateRequest& r, const OutputLimits& limits) {
  if (!r.adaptive()) return;
  const double states = (2.0 * r.frames + 2.0) * state_values(r.problem);
  const double room = std::floor((static_cast<double>(limits.max_values) - states) / kStepValues);
  if (room >= 1 && room < r.max_steps) r.max_steps = static_cast<int>(room);
}

int fitting_frames(const IntegrateRequest& r, int wanted, const OutputLimits& limits) {
  const double steps = r.adaptive() ? r.max_steps : std::ceil(r.t_end / *r.h);
  const double per_frame = (r.adaptive() ? 2.0 : 1.0) * state_values(r.problem);
  const double room = std::floor((static_cast<double>(limits.max_values) - steps * kStepValues) / per_frame) - 2;
  return std::max(r.frames, static_cast<int>(std::min<double>(wanted, room)));
}

void check_output(const SweepRequest& r, const OutputLimits& limits) {
  const double cells = static_cast<double>(r.methods.size()) * static_cast<double>(r.n.size()) * static_cast<double>(r.h.size());
  refuse_beyond(cells * kCellValues, limits, "h", "this sweep grid");
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

}  // namespace lienewton::service
