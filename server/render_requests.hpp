#pragma once
// Render requests, shared by the HTTP routes and the CLI: a solve/integrate/sweep request (or a finished
// sweep) plus picture options -> PNG bytes. Transport-neutral: capacity, deadlines and metrics come in as hooks.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/fields.hpp"
#include "core/group_registry.hpp"
#include "server/json_codec.hpp"
#include "server/output_limits.hpp"

namespace lienewton::render { class Renderer; }

namespace lienewton::service {

struct RenderHooks {
  // The JSON routes' caps on what a result holds, applied to what a picture keeps (iterates, frames, cells,
  // pixels); none: uncapped (the CLI). The server takes its work slot before a render parses anything.
  std::optional<OutputLimits> output;
  std::function<bool(int index)> keep_going;                 // per iteration/step/cell; false cancels
  std::function<void(const SweepCell&)> on_cell;             // sweep cells, for metrics
  std::function<void(const SolveResult&)> on_solve;          // finished solve, for metrics
  std::function<void(const IntegrateResult&)> on_integration;  // a finished integration drawn (its warnings)
};

// The response header of a render that drew an integration with warnings: their codes, comma-separated.
inline constexpr const char* kWarningsHeader = "X-Lienewton-Warnings";

// Thrown when keep_going returned false.
struct RenderCancelled {};

// Whether the group draws bodies (frames, motion) at index n: its body_frames of a seeded element are not empty.
bool draws_bodies(const GroupFamily& family, int n);
// The indices at which it does, for the dashboard's catalog: nullopt for every index it takes (SE(3), SExR^k),
// else those among 2..kBodiesIndicesTried (SO(N): {3}; none: empty).
inline constexpr int kBodiesIndicesTried = 8;
std::optional<std::vector<int>> bodies_at(const GroupFamily& family);

// Frames: a SolveRequest (n = 3, iterates drawn) or an IntegrateRequest (kind = "integrate", or any of
// integrator/t_end/frames present; frames defaults to 16), plus width/height/azimuth_deg/elevation_deg and upto
// (draw frames 0..upto only, for a slider over iterates or time steps; 422 naming upto if there are fewer).
// N != 3 throws ApiError 422. Throws FieldError/RequestError for invalid requests.
std::vector<unsigned char> render_frames(json request, const Limits& limits, render::Renderer& renderer,
                                         const RenderHooks& hooks);
// Motion: the same requests as frames (an integration's frames default to kMotionFrames; a solve's iterates are
// shown, at most kMotionFrames + 1 of them evenly spaced), drawn as a scene of bodies (render/motion_of_problem.hpp);
// format webp (the default) animates them, frame_ms each, its XMP naming each frame's t or n; png or svg shows the
// frame upto (default the last).
inline constexpr int kMotionFrames = 100;
inline constexpr int kMotionFrameMs = 50;
std::vector<unsigned char> render_motion(json request, const Limits& limits, render::Renderer& renderer,
                                         const RenderHooks& hooks);
// Heatmap: a SweepRequest or {"sweep": SweepResult}, plus metric/width/height (0 or absent: automatic).
std::vector<unsigned char> render_heatmap(json request, const Limits& limits, render::Renderer& renderer,
                                          const RenderHooks& hooks);
// Basin map: a BasinRequest plus width/height (0 or absent: automatic); one panel per method.
std::vector<unsigned char> render_basins(json request, const Limits& limits, render::Renderer& renderer,
                                         const RenderHooks& hooks);
// A figure's size when the request gives none.
struct FigureSize {
  int width;
  int height;
};
inline constexpr FigureSize kWorkPrecisionFigure{960, 640};
inline constexpr FigureSize kResidualsFigure{1200, 520};
inline constexpr FigureSize kInvariantsFigure{960, 560};

// Work-precision diagram: a WorkPrecisionRequest plus width/height (default kWorkPrecisionFigure).
std::vector<unsigned char> render_work_precision(json request, const Limits& limits, render::Renderer& renderer,
                                                 const RenderHooks& hooks);
// Residuals against solver CPU time and iteration: a SolveRequest without method/differential, plus
// methods/differentials lists (default: all; fixed point once) and width/height (default kResidualsFigure).
std::vector<unsigned char> render_residuals(json request, const Limits& limits, render::Renderer& renderer,
                                            const RenderHooks& hooks);

// Invariants' drift over time: an IntegrateRequest of a problem with invariants (422 naming problem otherwise),
// plus width/height (default kInvariantsFigure).
// The built-in problems that report invariants and which, in words, from core/invariants.hpp's table.
std::string problems_with_invariants();
std::vector<unsigned char> render_invariants(json request, const Limits& limits, render::Renderer& renderer,
                                             const RenderHooks& hooks);

// The picture options of the render routes, rows of the request contract (core/fields.hpp) like the fields of
// the requests they draw: each render route takes these rows plus its base request's.
const std::vector<fields::Field>& picture_fields();

// Any of the above.
using RenderRequestFn = std::vector<unsigned char> (*)(json, const Limits&, render::Renderer&, const RenderHooks&);

// The render routes by name (render/NAME, lienewton render NAME): the request they draw, their picture options'
// route, their function, and whether an integration's fields are taken beside the base request's (frames, motion).
struct RenderRoute {
  const char* name;
  fields::Route base;
  fields::Route picture;
  RenderRequestFn draw;
  bool integrations_too = false;
};
const std::vector<RenderRoute>& render_routes();
const RenderRoute* find_render_route(std::string_view name);

}  // namespace lienewton::service
