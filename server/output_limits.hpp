#pragma once
// Caps on what a request may make the server produce, checked after validation and before any work: a
// result's numbers (iterates x N^2, frames x N^2, steps, sweep cells) and a render's pixels. Beyond a cap the
// request is refused with 413 "output_too_large" naming the field to change.
#include <cstddef>

#include "core/basins.hpp"
#include "core/integrate.hpp"
#include "core/solve.hpp"
#include "core/sweep.hpp"
#include "server/json_codec.hpp"
#include "server/request_runner.hpp"

namespace lienewton::service {

// Numbers a basin map's result holds per pixel and method (status, root, iterations).
inline constexpr double kBasinPixelValues = 3;

struct OutputLimits {
  std::size_t max_values = 1'000'000;        // numbers in one result (about 20 MB of JSON)
  std::size_t max_image_pixels = 4'194'304;  // width x height of one PNG (2048 x 2048)
};

void check_output(const SolveRequest& request, const OutputLimits& limits);
void check_output(const IntegrateRequest& request, const OutputLimits& limits);
// Adaptive steps, whose number is not known ahead: lowers max_steps to the records that fit the cap with the
// frames (a run that reaches it ends with status max_steps, naming the bound).
void fit_output(IntegrateRequest& request, const OutputLimits& limits);
void check_output(const SweepRequest& request, const OutputLimits& limits);
void check_output(const BasinRequest& request, const OutputLimits& limits);
// The caps a request's type has, an integration's output fitted to them first (a work-precision diagram has
// none of its own): for the JSON routes and for what a picture keeps.
template <class Request>
void apply_output_limits(Request& request, const OutputLimits& limits) {
  if constexpr (requires { fit_output(request, limits); }) fit_output(request, limits);
  if constexpr (requires { check_output(request, limits); }) check_output(request, limits);
}
// The same on a prepared request: the server's JSON routes, before any work.
void apply_output_limits(PreparedRequest& request, const OutputLimits& limits);
// The most states up to `wanted` an integration may keep within the cap beside its steps (at least its frames).
int fitting_frames(const IntegrateRequest& request, int wanted, const OutputLimits& limits);
// width x height of a render request, where both are given as integers (else the parser judges them).
void check_image_pixels(const json& body, const OutputLimits& limits);

}  // namespace lienewton::service
