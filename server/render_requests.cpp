#include "server/render_requests.hpp"

#include <algorithm>
#include <climits>
#include <cstdio>
#include <stdexcept>

#include "core/integrators/methods.hpp"
#include "core/basins.hpp"
#include "core/group_registry.hpp"
#include "core/integrate.hpp"
#include "core/solve.hpp"
#include "core/sweep.hpp"
#include "core/work_precision.hpp"
#include "render/invariants_scene.hpp"
#include "render/log_axis.hpp"
#include "render/motion_of_problem.hpp"
#include "render/residuals_scene.hpp"
#include "render/work_precision_scene.hpp"
#include "render/renderer.hpp"
#include "server/http_errors.hpp"

namespace lienewton::service {
namespace {

const fields::Field& picture(std::string_view name) {
  for (const fields::Field& f : picture_fields())
    if (f.name == name) return f;
  throw std::logic_error("no picture option " + std::string(name));
}

// Takes an integer picture option out of the request (the rest goes to the request codec).
int take_int(json& request, const char* field, int fallback, bool zero_ok) {
  auto it = request.find(field);
  if (it == request.end() || it->is_null()) {
    if (it != request.end()) request.erase(it);
    return fallback;
  }
  const fields::Field& row = picture(field);
  const long long lo = static_cast<long long>(*row.minimum);
  const long long hi = row.maximum ? static_cast<long long>(*row.maximum) : INT_MAX;
  const std::string message = row.integer_message(field, hi) + (zero_ok ? " or 0 for automatic" : "");
  if (!it->is_number_integer()) throw FieldError("invalid_field", field, message);
  const auto v = it->is_number_unsigned() ? static_cast<long long>(std::min<std::uint64_t>(it->get<std::uint64_t>(), LLONG_MAX))
                                          : it->get<std::int64_t>();
  if (!((v >= lo && v <= hi) || (zero_ok && v == 0))) throw FieldError("invalid_field", field, message);
  request.erase(it);
  return static_cast<int>(v);
}

double take_angle(json& request, const char* field, double fallback) {
  auto it = request.find(field);
  if (it == request.end() || it->is_null()) {
    if (it != request.end()) request.erase(it);
    return fallback;
  }
  const fields::Field& row = picture(field);
  const std::string message = std::string(field) + " must be a finite number of degrees in [" +
                              fields::format_bound(*row.minimum) + ", " + fields::format_bound(*row.maximum) + "]";
  if (!it->is_number()) throw FieldError("invalid_field", field, message);
  const double v = it->get<double>();
  if (!(v >= *row.minimum && v <= *row.maximum)) throw FieldError("invalid_field", field, message);
  request.erase(it);
  return v;
}

std::string take_string(json& request, const char* field) {
  auto it = request.find(field);
  if (it == request.end() || it->is_null()) {
    if (it != request.end()) request.erase(it);
    return "";
  }
  if (!it->is_string()) throw FieldError("invalid_field", field, std::string(field) + " must be a string");
  std::string v = it->get<std::string>();
  request.erase(it);
  return v;
}

// Frames are the body axes of each state, as its group gives them (GroupFamily::body_frames): one rotation part
// (SO(3), SE(3), SO(3) x R^3, SE(3) x R^6, where n is 3) or a system of bodies ((SE(3) x R^6)^k).
void check_bodies(const ProblemSpec& p) {
  const GroupFamily& family = p.family();
  const std::string why =
      "rotation frames are drawn for groups with a rotation part (SO(3), SE(3), SOxR, SExR) or bodies (SExR^k): ";
  if (draws_bodies(family, p.n)) return;
  // SO(3) has frames and SO(4) none: the index is what is wrong.
  if (const std::optional<std::vector<int>> at = bodies_at(family); at && !at->empty()) {
    std::string list;
    for (int n : *at) list += (list.empty() ? "" : " or ") + std::to_string(n);
    throw ApiError(422, "unprocessable", "n", why + "n must be " + list);
  }
  throw ApiError(422, "unprocessable", "group", why + family.title(p.n) + " has none");
}

// Every state's bodies (check_bodies has accepted the group).
std::vector<std::vector<BodyFrame>> bodies(const ProblemSpec& p, const std::vector<Eigen::MatrixXd>& states) {
  const GroupFamily& family = p.family();
  std::vector<std::vector<BodyFrame>> out;
  for (const Eigen::MatrixXd& y : states) out.push_back(family.body_frames(p.n, y));
  return out;
}

// The caps of the request's JSON route on what the picture keeps.
template <class Request>
void cap_output(Request& request, const RenderHooks& hooks) {
  if (hooks.output) apply_output_limits(request, *hooks.output);
}

bool keep_going(const RenderHooks& hooks, int index) { return !hooks.keep_going || hooks.keep_going(index); }

// A list of enum names taken out of the request; all values when absent. Repeats are dropped.
template <class E, std::size_t K>
std::vector<E> take_enum_list(json& request, const char* field, std::optional<E> (*parse)(std::string_view),
                              const E (&all)[K]) {
  auto it = request.find(field);
  if (it == request.end() || it->is_null()) {
    if (it != request.end()) request.erase(it);
    return {std::begin(all), std::end(all)};
  }
  std::string names;
  for (E e : all) names += (names.empty() ? "" : ", ") + std::string(to_string(e));
  const std::string message = std::string(field) + " must be a non-empty list of " + names;
  if (!it->is_array() || it->empty() || it->size() > picture(field).max_items)
    throw FieldError("invalid_field", field, message);
  std::vector<E> out;
  for (const json& v : *it) {
    const std::optional<E> e = v.is_string() ? parse(v.get<std::string>()) : std::nullopt;
    if (!e) throw FieldError("invalid_field", field, message);
    if (std::find(out.begin(), out.end(), *e) == out.end()) out.push_back(*e);
  }
  request.erase(it);
  return out;
}

std::string group_name(const ProblemSpec& p) { return p.family().title(p.n); }

// The picture's format: png unless the request says svg.
render::ImageFormat take_format(json& request) {
  const std::string format = take_string(request, "format");
  if (format.empty() || format == "png") return render::ImageFormat::png;
  if (format == "svg") return render::ImageFormat::svg;
  throw FieldError("invalid_field", "format", "format must be png or svg");
}

std::string number_text(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", x);
  return text;
}

// "lo…hi" of a grid's values, or its one value.
template <class T, class Text>
std::string span(const std::vector<T>& values, Text text) {
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  return *lo == *hi ? text(*lo) : text(*lo) + "\u2026" + text(*hi);
}

std::string field_name(const ProblemSpec& p) { return p.g ? "your g(y)" : std::string(to_string(p.kind)); }

bool any_newton(const std::vector<Method>& methods) {
  return std::any_of(methods.begin(), methods.end(), [](Method m) { return m != Method::fixed_point; });
}

// The solver's facts a picture depends on: the differential (when a Newton method forms one), tol, the iteration
// cap and the variants.
std::string solver_facts(const SolverOptions& s, bool newton) {
  std::string out;
  if (newton) out += "differential " + std::string(words(s.differential).short_label) + " \u00b7 ";
  out += "tol " + number_text(s.tol) + " \u00b7 at most " + std::to_string(s.max_iterations) + " iterations";
  if (s.globalization != Globalization::none) out += " \u00b7 " + std::string(words(s.globalization).short_label);
  if (s.continuation) out += " \u00b7 continuation in h";
  return out;
}

// The group of a grid over N: "SO(3)" for one N, "SO(N)" for several.
std::string group_text(const ProblemSpec& p, const std::vector<int>& n) {
  const std::string first = p.family().title(n.front());
  if (std::all_of(n.begin(), n.end(), [&](int v) { return v == n.front(); })) return first;
  const std::size_t paren = first.find('(');
  return paren == std::string::npos ? first : first.substr(0, paren) + "(N)";
}

// The heatmap's caption: from the sweep request, or, for a finished sweep, from its cells alone.
render::Caption heatmap_caption(const SweepResult& result, const SweepRequest* request, render::HeatmapMetric metric) {
  std::vector<int> n;
  std::vector<double> h;
  for (const SweepCell& c : result.cells) {
    n.push_back(c.n);
    h.push_back(c.h);
  }
  if (n.empty()) return {};  // nothing to draw: the renderer refuses it
  const std::string grid = "N = " + span(n, [](int v) { return std::to_string(v); }) + " \u00b7 h = " + span(h, render::power_of_two_label);
  const std::string colour = "colour: " + std::string(render::words(metric).label);
  if (!request) return {"Where each method converges", grid + " \u00b7 " + colour};
  return {"Where each method converges: " + field_name(request->problem) + " on " + group_text(request->problem, n),
          grid + " \u00b7 " + solver_facts(request->solver, any_newton(request->methods)) + " \u00b7 " + colour};
}

// The basin map's caption: the problem, its group and h, the square of starts and the solver's facts.
render::Caption basins_caption(const BasinRequest& r, const BasinResult& map) {
  const SolveRequest& s = r.solve;
  const std::string size = std::to_string(map.grid.axis.size());
  const std::string radius = number_text(map.grid.radius);
  return {"From which starts each method converges: " + field_name(s.problem) + " on " + group_name(s.problem) +
              ", h = " + render::power_of_two_label(s.h),
          size + " \u00d7 " + size + " starts y\u2080 = z exp(a B\u2081 + b B\u2082), a, b in [\u2212" + radius + ", " +
              radius + "] \u00b7 " + solver_facts(s.solver, any_newton(r.methods))};
}

// The figure's PNG; a figure with nothing to draw (every run failed) is a 422.
template <class MakeFigure>
std::vector<unsigned char> draw_figure(render::Renderer& renderer, render::ImageFormat format, MakeFigure make) {
  render::Figure figure;
  try {
    figure = make();
  } catch (const std::invalid_argument& e) {
    throw ApiError(422, "unprocessable", "", std::string("nothing to draw: ") + e.what());
  }
  return renderer.figure_png(figure, format);
}

}  // namespace

const std::vector<RenderRoute>& render_routes() {
  static const std::vector<RenderRoute> routes{
      {"frames", fields::solve, fields::render_frames, render_frames, true},
      {"motion", fields::solve, fields::render_motion, render_motion, true},
      {"heatmap", fields::sweep, fields::render_heatmap, render_heatmap},
      {"basins", fields::basins, fields::render_basins, render_basins},
      {"work-precision", fields::work_precision, fields::render_work_precision, render_work_precision},
      {"residuals", fields::solve, fields::render_residuals, render_residuals},
      {"invariants", fields::integrate, fields::render_invariants, render_invariants}};
  return routes;
}

const RenderRoute* find_render_route(std::string_view name) {
  for (const RenderRoute& r : render_routes())
    if (name == r.name) return &r;
  return nullptr;
}

const std::vector<fields::Field>& picture_fields() {
  using fields::Field;
  using fields::Type;
  static const std::vector<Field> rows = [] {
    constexpr fields::Routes all = fields::render_frames | fields::render_heatmap | fields::render_basins |
                                   fields::render_work_precision | fields::render_residuals | fields::render_invariants |
                                   fields::render_motion;
    constexpr fields::Routes scenes = fields::render_frames | fields::render_motion;
    const Field size{.name = "width", .type = Type::integer, .routes = all,
                     .description = "image width in pixels (heatmap and basins: 0 or absent, automatic)",
                     .minimum = static_cast<double>(render::kMinImageSize),
                     .maximum = static_cast<double>(render::kMaxImageSize)};
    Field height = size;
    height.name = "height";
    height.description = "image height in pixels (heatmap and basins: 0 or absent, automatic)";
    const Field azimuth{.name = "azimuth_deg", .type = Type::number, .routes = scenes,
                        .description = "camera azimuth", .minimum = -360.0, .maximum = 360.0};
    Field elevation = azimuth;
    elevation.name = "elevation_deg";
    elevation.description = "camera elevation";
    // The residuals' lists: a value of the solve's method or differential per element.
    const auto list_of = [](const char* one, const char* name, const char* items) {
      Field list = *fields::find(fields::solve, one);
      list.name = name;
      list.routes = fields::render_residuals;
      list.lands = {};
      list.array = true;
      list.min_items = 1;
      list.max_items = 16;
      list.items = items;
      return list;
    };
    const Field methods = list_of("method", "methods", "method names");
    const Field differentials = list_of("differential", "differentials", "differential names");
    return std::vector<Field>{
        Field{.name = "kind", .type = Type::string, .routes = scenes,
              .description = "what is drawn: a solve's iterates or an integration's states (default: integrate when "
                             "any of integrator, t_end, frames is given)",
              .values = {"solve", "integrate"}},
        size, height,
        Field{.name = "format", .type = Type::string, .routes = all & ~fields::render_motion,
              .description = "png (the default), or svg: the same picture with its text and lines as vectors (a "
                             "basin map's panels as embedded PNG); the answer's type is image/svg+xml",
              .values = {"png", "svg"}},
        azimuth, elevation,
        Field{.name = "format", .type = Type::string, .routes = fields::render_motion,
              .description = "webp (the default): an animation of every state, frame_ms each, looping "
                             "(image/webp); png or svg: the scene at state upto (default the last)",
              .values = {"webp", "png", "svg"}},
        Field{.name = "upto", .type = Type::integer, .routes = scenes,
              .description = "frames: draw frames 0..upto only, upto bold (a slider over iterates or time steps); "
                             "motion: the state a png or svg shows; 422 if there are not that many",
              .minimum = 0.0},
        Field{.name = "frame_ms", .type = Type::integer, .routes = fields::render_motion,
              .description = "how long an animation shows each state, in milliseconds (default " +
                             std::to_string(kMotionFrameMs) + ")",
              .minimum = 1.0, .maximum = 10000.0},
        Field{.name = "sweep", .type = Type::object, .routes = fields::render_heatmap,
              .description = "a finished sweep to draw instead of running the sweep request; with the request's "
                             "fields beside it, the title names them (each cell must lie in that request's grid)",
              .schema = "SweepResult"},
        Field{.name = "metric", .type = Type::string, .routes = fields::render_heatmap,
              .description = "what colours a converged cell", .values = fields::names(render::kAllHeatmapMetrics)},
        methods, differentials};
  }();
  return rows;
}

namespace {

// What a frames or motion picture shows: the states of a solve's iterates or of an integration, with their
// times (a solve's: the iteration n), the start, the problem and the caption.
struct Shown {
  ProblemSpec problem;
  std::vector<Eigen::MatrixXd> states;
  std::vector<double> times;
  Eigen::MatrixXd start;
  render::Caption caption;
  bool iterates = false;
  int frames = 0;  // an integration's frames as asked for (the states may be denser: path_samples)
};

// What the picture draws: a solve or an integration, told apart by kind or by a field only integrate requests have.
bool takes_integration(json& request) {
  std::string kind = take_string(request, "kind");
  if (kind.empty()) {
    kind = request.contains("integrator") || request.contains("t_end") || request.contains("frames") ? "integrate" : "solve";
  }
  if (kind != "solve" && kind != "integrate") throw FieldError("invalid_field", "kind", "kind must be solve or integrate");
  return kind == "integrate";
}

// Runs the request the picture draws (an integration with `default_frames` states when frames is absent).
// The solve's iterates, or the integration's frames + 1 states; path_samples times as many (within the frames
// limits) when a picture draws a path through more states than it shows.
Shown run_shown(json& request, bool integration, const Limits& limits, const RenderHooks& hooks, int default_frames,
                int path_samples = 1) {
  Shown shown;
  if (!integration) {
    SolveRequest r = solve_request_from_json(request, limits);
    check_bodies(r.problem);
    r.solver.include_iterates = true;
    validate(r);
    cap_output(r, hooks);
    SolveResult result = solve_validated(r, [&](const TraceRecord& t) { return keep_going(hooks, t.iteration); });
    if (hooks.on_solve) hooks.on_solve(result);
    if (result.status == Status::cancelled) throw RenderCancelled{};
    for (const auto& t : result.trace)
      if (t.y.size() > 0) shown.states.push_back(t.y), shown.times.push_back(t.iteration);
    if (shown.states.empty()) shown.states.push_back(result.y), shown.times.push_back(0);
    shown.start = r.problem.z ? *r.problem.z : shown.states.front();
    shown.caption = {"Iterates y\u2080, y\u2081, \u2026 of " + std::string(words(r.solver.method).label),
                     field_name(r.problem) + " on " + group_name(r.problem) + ", h = " + render::power_of_two_label(r.h) +
                         " \u00b7 " + solver_facts(r.solver, r.solver.method != Method::fixed_point)};
    shown.problem = std::move(r.problem);
    shown.iterates = true;
    return shown;
  }
  if (!request.contains("frames")) request["frames"] = default_frames;
  IntegrateRequest r = integrate_request_from_json(request, limits);
  check_bodies(r.problem);
  if (r.frames < 1) throw FieldError("invalid_field", "frames", "frames must be at least 1 to draw a trajectory");
  shown.frames = r.frames;
  const int denser = std::max(r.frames, std::min({limits.max_frames, IntegrateRequest::kMaxFrames, path_samples * r.frames}));
  r.frames = hooks.output ? fitting_frames(r, denser, *hooks.output) : denser;
  r.reference = false;  // the picture needs no global error
  validate(r);
  cap_output(r, hooks);
  bool stopped = false;
  IntegrateResult result =
      integrate_validated(r, [&](const StepRecord& s) { return !(stopped = !keep_going(hooks, s.step)); });
  if (stopped) throw RenderCancelled{};
  if (hooks.on_integration) hooks.on_integration(result);
  shown.states = result.frames.empty() ? std::vector<Eigen::MatrixXd>{result.y} : result.frames;
  shown.times = result.frames.empty() ? std::vector<double>{r.t_end} : result.frame_times;
  shown.start = shown.states.front();
  const bool solves = solves_stages(r.integrator);  // rkmk4 is explicit: no method, differential or tol
  shown.caption = {"Trajectory y(t): " + std::string(words(r.integrator).label) +
                       (solves ? ", " + std::string(words(r.solver.method).label) : std::string()),
                   field_name(r.problem) + " on " + group_name(r.problem) + ", h = " + render::power_of_two_label(*r.h) +
                       ", t_end = " + number_text(r.t_end) +
                       (solves ? " \u00b7 " + solver_facts(r.solver, uses_differential(r.solver.method)) : std::string())};
  shown.problem = std::move(r.problem);
  return shown;
}

render::FramesOptions take_view(json& request) {
  render::FramesOptions options;
  options.width = take_int(request, "width", options.width, false);
  options.height = take_int(request, "height", options.height, false);
  options.azimuth_deg = take_angle(request, "azimuth_deg", options.azimuth_deg);
  options.elevation_deg = take_angle(request, "elevation_deg", options.elevation_deg);
  return options;
}

// upto: a slider's position, below the number of states (-1: absent).
void check_upto(int upto, std::size_t states) {
  if (upto >= static_cast<int>(states)) {
    throw ApiError(422, "unprocessable", "upto",
                   "upto must be below the number of frames (" + std::to_string(states) + ")");
  }
}

}  // namespace

bool draws_bodies(const GroupFamily& family, int n) { return !family.body_frames(n, family.random(n, 1)).empty(); }

std::optional<std::vector<int>> bodies_at(const GroupFamily& family) {
  if (const std::optional<int> only = family.only_index()) {
    if (draws_bodies(family, *only)) return std::nullopt;
    return std::vector<int>{};
  }
  std::vector<int> at;
  for (int n = 2; n <= kBodiesIndicesTried; ++n)
    if (draws_bodies(family, n)) at.push_back(n);
  if (at.size() == static_cast<std::size_t>(kBodiesIndicesTried - 1)) return std::nullopt;
  return at;
}

std::vector<unsigned char> render_frames(json request, const Limits& limits, render::Renderer& renderer,
                                         const RenderHooks& hooks) {
  if (!request.is_object()) throw FieldError("invalid_field", "", "the request must be a JSON object");
  const render::FramesOptions options = take_view(request);
  const render::ImageFormat format = take_format(request);
  // A slider's position: only frames 0..upto are drawn, upto bold (absent: all).
  const int upto = take_int(request, "upto", -1, false);
  const bool integration = takes_integration(request);
  Shown shown = run_shown(request, integration, limits, hooks, 16);
  check_upto(upto, shown.states.size());
  if (upto >= 0) shown.states.resize(static_cast<std::size_t>(upto) + 1);
  std::vector<std::vector<BodyFrame>> frames = bodies(shown.problem, shown.states);
  const std::vector<BodyFrame> start = bodies(shown.problem, {shown.start}).front();
  // One body is its rotation in the unit sphere; several are their axes at their positions.
  if (start.size() > 1) return renderer.frames_png(frames, start, options, shown.caption, format);
  std::vector<Eigen::Matrix3d> rotations;
  for (const auto& state : frames) rotations.push_back(state.front().rotation);
  return renderer.frames_png(rotations, start.front().rotation, options, shown.caption, format);
}

std::vector<unsigned char> render_motion(json request, const Limits& limits, render::Renderer& renderer,
                                         const RenderHooks& hooks) {
  if (!request.is_object()) throw FieldError("invalid_field", "", "the request must be a JSON object");
  const render::FramesOptions options = take_view(request);
  const std::string format = take_string(request, "format");
  if (!format.empty() && format != "webp" && format != "png" && format != "svg")
    throw FieldError("invalid_field", "format", "format must be webp, png or svg");
  const int upto = take_int(request, "upto", -1, false);
  const int frame_ms = take_int(request, "frame_ms", kMotionFrameMs, false);
  // The path is drawn through kPathSamples times as many states as the animation shows (as many as the frames
  // limit allows): a fast spin's loops stay round between two frames.
  constexpr int kPathSamples = 8;
  const bool integration = takes_integration(request);
  const Shown shown = run_shown(request, integration, limits, hooks, kMotionFrames, kPathSamples);
  const int frames = integration ? shown.frames : kMotionFrames;
  // The states shown: `frames` + 1 evenly spaced (a solve's: kMotionFrames + 1 of its iterates, so that 10000
  // iterations cost no more to draw than 100), first and last included; the file's metadata names each one's t or n.
  std::vector<std::size_t> states;
  const std::size_t dense = shown.states.size();
  const std::size_t count = std::min<std::size_t>(dense, static_cast<std::size_t>(frames) + 1);
  for (std::size_t i = 0; i < count; ++i) states.push_back(count == 1 ? dense - 1 : i * (dense - 1) / (count - 1));
  check_upto(upto, states.size());
  render::Motion motion = render::motion_of(shown.problem, shown.states, shown.times);
  if (shown.iterates) motion.time_name = "n";
  if (format.empty() || format == "webp") {
    std::vector<unsigned char> out = renderer.motion_webp(motion, states, options, shown.caption, frame_ms,
                                                          [&](std::size_t i) { return keep_going(hooks, static_cast<int>(i)); });
    if (out.empty()) throw RenderCancelled{};
    return out;
  }
  const std::size_t at = upto >= 0 ? states[static_cast<std::size_t>(upto)] : dense - 1;
  return renderer.motion_png(motion, at, options, shown.caption,
                             format == "svg" ? render::ImageFormat::svg : render::ImageFormat::png);
}

std::vector<unsigned char> render_heatmap(json request, const Limits& limits, render::Renderer& renderer,
                                          const RenderHooks& hooks) {
  if (!request.is_object()) throw FieldError("invalid_field", "", "the request must be a JSON object");
  render::HeatmapOptions options;
  options.width = take_int(request, "width", 0, true);
  options.height = take_int(request, "height", 0, true);
  const render::ImageFormat format = take_format(request);
  if (const std::string metric = take_string(request, "metric"); !metric.empty()) {
    auto parsed = render::heatmap_metric_from_string(metric);
    if (!parsed) {
      std::string names;
      for (const std::string& name : picture("metric").values) names += (names.empty() ? "" : ", ") + name;
      throw FieldError("invalid_field", "metric", "metric must be one of " + names);
    }
    options.metric = *parsed;
  }
  if (request.contains("sweep")) {
    const SweepResult result = sweep_result_from_json(request["sweep"], limits);
    request.erase("sweep");
    if (request.empty()) {
      return renderer.heatmap_png(result, options, heatmap_caption(result, nullptr, options.metric), format);
    }
    // The request the cells came from, for the title: it must at least hold every cell in its grid.
    SweepRequest r = sweep_request_from_json(request, limits);
    validate(r);
    for (std::size_t i = 0; i < result.cells.size(); ++i) {
      const SweepCell& c = result.cells[i];
      const auto in = [](const auto& list, const auto& v) { return std::find(list.begin(), list.end(), v) != list.end(); };
      if (!in(r.methods, c.method) || !in(r.n, c.n) || !in(r.h, c.h)) {
        throw FieldError("invalid_field", "sweep.cells[" + std::to_string(i) + "]",
                         "this cell (" + std::string(to_string(c.method)) + ", n " + std::to_string(c.n) + ", h " +
                             number_text(c.h) + ") is not in the grid of the request beside it");
      }
    }
    return renderer.heatmap_png(result, options, heatmap_caption(result, &r, options.metric), format);
  }
  SweepRequest r = sweep_request_from_json(request, limits);
  validate(r);
  cap_output(r, hooks);
  int index = 0;
  bool stopped = false;
  const SweepResult result = sweep_validated(r, [&](const SweepCell& cell) {
    if (hooks.on_cell) hooks.on_cell(cell);
    return !(stopped = !keep_going(hooks, index++));
  });
  // Cells cancelled by the deadline never reach the callback: a sweep short of its cells was stopped.
  const std::size_t cells = r.shard ? shard_cells(r, *r.shard).size() : result.grid_cells;
  if (stopped || result.cells.size() != cells) throw RenderCancelled{};
  return renderer.heatmap_png(result, options, heatmap_caption(result, &r, options.metric), format);
}

std::vector<unsigned char> render_basins(json request, const Limits& limits, render::Renderer& renderer,
                                         const RenderHooks& hooks) {
  if (!request.is_object()) throw FieldError("invalid_field", "", "the request must be a JSON object");
  const int width = take_int(request, "width", 0, true);
  const int height = take_int(request, "height", 0, true);
  const render::ImageFormat format = take_format(request);
  BasinRequest r = basin_request_from_json(request, limits);
  validate(r);
  cap_output(r, hooks);
  int index = 0;
  bool stopped = false;
  const BasinResult map = basins_validated(r, [&](const BasinRow& row, const std::vector<BasinRoot>&) {
    if (hooks.on_cell) {  // every pixel is a solve, counted in the metrics as a sweep cell is
      SweepCell counted;
      for (const auto& pixels : row.pixels)
        for (const BasinPixel& p : pixels) {
          counted.status = p.status;
          counted.iterations = p.iterations;
          hooks.on_cell(counted);
        }
    }
    return !(stopped = !keep_going(hooks, index++));
  });
  if (stopped || !map.complete) throw RenderCancelled{};
  return renderer.basins_png(map, width, height, basins_caption(r, map), format);
}

std::vector<unsigned char> render_work_precision(json request, const Limits& limits, render::Renderer& renderer,
                                                 const RenderHooks& hooks) {
  if (!request.is_object()) throw FieldError("invalid_field", "", "the request must be a JSON object");
  const int width = take_int(request, "width", kWorkPrecisionFigure.width, false);
  const int height = take_int(request, "height", kWorkPrecisionFigure.height, false);
  const render::ImageFormat format = take_format(request);
  WorkPrecisionRequest r = work_precision_request_from_json(request, limits);
  validate(r);
  int index = 0;
  bool stopped = false;
  const WorkPrecisionResult result = work_precision_validated(r, [&](const WorkPrecisionSeries&) {
    return !(stopped = !keep_going(hooks, index++));
  });
  if (stopped) throw RenderCancelled{};
  const std::string title = "Work-precision: " + r.problem.name() + " on " +
                            group_name(r.problem) + ", t_end = " + number_text(r.t_end);
  return draw_figure(renderer, format, [&] { return render::work_precision_scene(result, title, width, height); });
}

std::string problems_with_invariants() {
  std::string out;
  for (ProblemKind kind : kAllProblems) {
    const auto kept = invariants_of(kind);
    if (kept.empty()) continue;
    out += (out.empty() ? "" : ", ") + std::string(to_string(kind)) + " (";
    for (std::size_t i = 0; i < kept.size(); ++i) out += (i ? ", " : "") + std::string(to_string(kept[i]));
    out += ")";
  }
  return out + ", where its parameters keep them (a damped chain loses its energy)";
}

std::vector<unsigned char> render_invariants(json request, const Limits& limits, render::Renderer& renderer,
                                             const RenderHooks& hooks) {
  if (!request.is_object()) throw FieldError("invalid_field", "", "the request must be a JSON object");
  const int width = take_int(request, "width", kInvariantsFigure.width, false);
  const int height = take_int(request, "height", kInvariantsFigure.height, false);
  const render::ImageFormat format = take_format(request);
  IntegrateRequest r = integrate_request_from_json(request, limits);
  r.reference = false;  // the picture needs no global error
  validate(r);
  cap_output(r, hooks);
  if (!has_invariants(r.problem))
    throw ApiError(422, "unprocessable", "problem", field_name(r.problem) + " reports no invariants; these do: " +
                                                    problems_with_invariants());
  bool stopped = false;
  const IntegrateResult result =
      integrate_validated(r, [&](const StepRecord& s) { return !(stopped = !keep_going(hooks, s.step)); });
  if (stopped) throw RenderCancelled{};
  if (hooks.on_integration) hooks.on_integration(result);
  if (result.status != Status::converged)
    throw ApiError(422, "unprocessable", "h", "the integration ended " + std::string(to_string(result.status)) +
                                                  ": " + result.reason);
  const std::string title = "Invariants' drift: " + std::string(words(r.integrator).short_label) + ", " +
                            field_name(r.problem) + " on " + group_name(r.problem) + ", h = " +
                            render::power_of_two_label(*r.h) + ", t_end = " + number_text(r.t_end);
  return draw_figure(renderer, format, [&] { return render::invariants_scene(result, title, width, height); });
}

std::vector<unsigned char> render_residuals(json request, const Limits& limits, render::Renderer& renderer,
                                            const RenderHooks& hooks) {
  if (!request.is_object()) throw FieldError("invalid_field", "", "the request must be a JSON object");
  const int width = take_int(request, "width", kResidualsFigure.width, false);
  const int height = take_int(request, "height", kResidualsFigure.height, false);
  const render::ImageFormat format = take_format(request);
  const std::vector<Method> methods = take_enum_list(request, "methods", method_from_string, kAllMethods);
  const std::vector<Differential> differentials =
      take_enum_list(request, "differentials", differential_from_string, kAllDifferentials);
  for (const char* one : {"method", "differential"}) {
    if (request.contains(one)) {
      throw FieldError("unknown_field", one, std::string(one) + " is chosen by the lists " + one + "s here");
    }
  }
  SolveRequest base = solve_request_from_json(request, limits);
  validate(base);
  std::vector<render::ResidualRun> runs;
  int index = 0;
  for (Method m : methods) {
    for (Differential d : differentials) {
      // Fixed point (1.2) forms no differential: one run, whatever differentials lists.
      if (m == Method::fixed_point && d != differentials.front()) continue;
      SolveRequest r = base;
      r.solver.method = m;
      r.solver.differential = d;
      const SolveResult result = solve(r, [&](const TraceRecord&) { return keep_going(hooks, index++); });
      if (hooks.on_solve) hooks.on_solve(result);
      if (result.status == Status::cancelled) throw RenderCancelled{};
      render::ResidualRun run{.method = m, .differential = d, .status = result.status, .cpu_seconds = {}, .residual = {}};
      for (const TraceRecord& t : result.trace) {
        run.cpu_seconds.push_back(t.cpu_seconds);
        run.residual.push_back(t.residual);
      }
      runs.push_back(std::move(run));
    }
  }
  const std::string title = "\u2016f(y\u2099)\u2016 against solver CPU time: " + base.problem.name() + " on " +
                            group_name(base.problem) + ", h = " + number_text(base.h);
  return draw_figure(renderer, format, [&] { return render::residuals_scene(runs, title, width, height); });
}

}  // namespace lienewton::service
