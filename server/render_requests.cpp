#include "server/render_requests.hpp"

#include <algorithm>
#include <climits>
#include <cstdio>
#include <stdexcept>

#include "core/basins.hpp"
#include "core/group_registry.hpp"
#include "core/integrate.hpp"
#include "core/solve.hpp"
#include "core/sweep.hpp"
#include "core/work_precision.hpp"
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

// Frames are rotations: SO(3), the default group at n = 3.
void check_so3(const ProblemSpec& p) {
  const std::string why = "rotation frames are drawn for SO(3) only: ";
  if (p.group != ProblemSpec{}.group)
    throw ApiError(422, "unprocessable", "group", why + "group must be " + ProblemSpec{}.group);
  if (p.n != 3) throw ApiError(422, "unprocessable", "n", why + "n must be 3");
}

void before_work(const RenderHooks& hooks) {
  if (hooks.before_work) hooks.before_work();
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

std::string group_name(const ProblemSpec& p) { return group_family(p.group).title(p.n); }

std::string number_text(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", x);
  return text;
}

// The figure's PNG; a figure with nothing to draw (every run failed) is a 422.
template <class MakeFigure>
std::vector<unsigned char> draw_figure(render::Renderer& renderer, MakeFigure make) {
  render::Figure figure;
  try {
    figure = make();
  } catch (const std::invalid_argument& e) {
    throw ApiError(422, "unprocessable", "", std::string("nothing to draw: ") + e.what());
  }
  return renderer.figure_png(figure);
}

}  // namespace

const std::vector<fields::Field>& picture_fields() {
  using fields::Field;
  using fields::Type;
  static const std::vector<Field> rows = [] {
    constexpr fields::Routes all = fields::render_frames | fields::render_heatmap | fields::render_basins | fields::render_work_precision | fields::render_residuals;
    const Field size{.name = "width", .type = Type::integer, .routes = all,
                     .description = "image width in pixels (heatmap and basins: 0 or absent, automatic)",
                     .minimum = static_cast<double>(render::kMinImageSize),
                     .maximum = static_cast<double>(render::kMaxImageSize)};
    Field height = size;
    height.name = "height";
    height.description = "image height in pixels (heatmap and basins: 0 or absent, automatic)";
    const Field azimuth{.name = "azimuth_deg", .type = Type::number, .routes = fields::render_frames,
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
        Field{.name = "kind", .type = Type::string, .routes = fields::render_frames,
              .description = "what is drawn: a solve's iterates or an integration's states (default: integrate when "
                             "any of integrator, t_end, frames is given)",
              .values = {"solve", "integrate"}},
        size, height, azimuth, elevation,
        Field{.name = "upto", .type = Type::integer, .routes = fields::render_frames,
              .description = "draw frames 0..upto only, upto bold (a slider over iterates or time steps); 422 if "
                             "there are not that many",
              .minimum = 0.0},
        Field{.name = "sweep", .type = Type::object, .routes = fields::render_heatmap,
              .description = "a finished sweep to draw instead of a sweep request", .schema = "SweepResult"},
        Field{.name = "metric", .type = Type::string, .routes = fields::render_heatmap,
              .description = "what colours a converged cell", .values = fields::names(render::kAllHeatmapMetrics)},
        methods, differentials};
  }();
  return rows;
}

std::vector<unsigned char> render_frames(json request, const Limits& limits, render::Renderer& renderer,
                                         const RenderHooks& hooks) {
  if (!request.is_object()) throw FieldError("invalid_field", "", "the request must be a JSON object");
  render::FramesOptions options;
  options.width = take_int(request, "width", options.width, false);
  options.height = take_int(request, "height", options.height, false);
  options.azimuth_deg = take_angle(request, "azimuth_deg", options.azimuth_deg);
  options.elevation_deg = take_angle(request, "elevation_deg", options.elevation_deg);
  // A slider's position: only frames 0..upto are drawn, upto bold (absent: all).
  const int upto = take_int(request, "upto", -1, false);
  const auto draw = [&](std::vector<Eigen::Matrix3d>& frames, const Eigen::Matrix3d& start) {
    if (upto >= static_cast<int>(frames.size())) {
      throw ApiError(422, "unprocessable", "upto", "upto must be below the number of frames (" +
                                                       std::to_string(frames.size()) + ")");
    }
    if (upto >= 0) frames.resize(static_cast<std::size_t>(upto) + 1);
    return renderer.frames_png(frames, start, options);
  };
  // An integrate request is told apart by kind, or by a field only integrate requests have.
  std::string kind = take_string(request, "kind");
  if (kind.empty()) {
    kind = request.contains("integrator") || request.contains("t_end") || request.contains("frames") ? "integrate" : "solve";
  }
  std::vector<Eigen::Matrix3d> frames;
  Eigen::Matrix3d start;
  if (kind == "solve") {
    SolveRequest r = solve_request_from_json(request, limits);
    check_so3(r.problem);
    r.solver.include_iterates = true;
    validate(r);
    before_work(hooks);
    SolveResult result = solve(r, [&](const TraceRecord& t) { return keep_going(hooks, t.iteration); });
    if (hooks.on_solve) hooks.on_solve(result);
    if (result.status == Status::cancelled) throw RenderCancelled{};
    for (const auto& t : result.trace) {
      if (t.y.rows() == 3 && t.y.cols() == 3) frames.emplace_back(t.y);
    }
    if (frames.empty()) frames.emplace_back(result.y);
    start = r.problem.z ? Eigen::Matrix3d(*r.problem.z) : frames.front();
    return draw(frames, start);
  }
  if (kind != "integrate") throw FieldError("invalid_field", "kind", "kind must be solve or integrate");
  if (!request.contains("frames")) request["frames"] = 16;
  IntegrateRequest r = integrate_request_from_json(request, limits);
  check_so3(r.problem);
  if (r.frames < 1) throw FieldError("invalid_field", "frames", "frames must be at least 1 to draw a trajectory");
  r.reference = false;  // the picture needs no global error
  validate(r);
  before_work(hooks);
  bool stopped = false;
  IntegrateResult result = integrate(r, [&](const StepRecord& s) { return !(stopped = !keep_going(hooks, s.step)); });
  if (stopped) throw RenderCancelled{};
  for (const auto& m : result.frames) {
    if (m.rows() == 3 && m.cols() == 3) frames.emplace_back(m);
  }
  if (frames.empty()) frames.emplace_back(result.y);
  start = frames.front();
  return draw(frames, start);
}

std::vector<unsigned char> render_heatmap(json request, const Limits& limits, render::Renderer& renderer,
                                          const RenderHooks& hooks) {
  if (!request.is_object()) throw FieldError("invalid_field", "", "the request must be a JSON object");
  render::HeatmapOptions options;
  options.width = take_int(request, "width", 0, true);
  options.height = take_int(request, "height", 0, true);
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
    if (request.size() != 1) {
      for (const auto& [key, _] : request.items()) {
        if (key != "sweep") throw FieldError("unknown_field", key, "unknown field " + key + " next to sweep");
      }
    }
    const SweepResult result = sweep_result_from_json(request["sweep"], limits);
    before_work(hooks);
    return renderer.heatmap_png(result, options);
  }
  SweepRequest r = sweep_request_from_json(request, limits);
  validate(r);
  before_work(hooks);
  int index = 0;
  bool stopped = false;
  const SweepResult result = sweep(r, [&](const SweepCell& cell) {
    if (hooks.on_cell) hooks.on_cell(cell);
    return !(stopped = !keep_going(hooks, index++));
  });
  if (stopped) throw RenderCancelled{};
  return renderer.heatmap_png(result, options);
}

std::vector<unsigned char> render_basins(json request, const Limits& limits, render::Renderer& renderer,
                                         const RenderHooks& hooks) {
  if (!request.is_object()) throw FieldError("invalid_field", "", "the request must be a JSON object");
  const int width = take_int(request, "width", 0, true);
  const int height = take_int(request, "height", 0, true);
  BasinRequest r = basin_request_from_json(request, limits);
  validate(r);
  before_work(hooks);
  int index = 0;
  bool stopped = false;
  const BasinResult map = basins(r, [&](const BasinRow& row, const std::vector<BasinRoot>&) {
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
  return renderer.basins_png(map, width, height);
}

std::vector<unsigned char> render_work_precision(json request, const Limits& limits, render::Renderer& renderer,
                                                 const RenderHooks& hooks) {
  if (!request.is_object()) throw FieldError("invalid_field", "", "the request must be a JSON object");
  const int width = take_int(request, "width", kWorkPrecisionFigure.width, false);
  const int height = take_int(request, "height", kWorkPrecisionFigure.height, false);
  WorkPrecisionRequest r = work_precision_request_from_json(request, limits);
  validate(r);
  before_work(hooks);
  int index = 0;
  bool stopped = false;
  const WorkPrecisionResult result = work_precision(r, [&](const WorkPrecisionSeries&) {
    return !(stopped = !keep_going(hooks, index++));
  });
  if (stopped) throw RenderCancelled{};
  const std::string title = "Work-precision: " + std::string(to_string(r.problem.kind)) + " on " +
                            group_name(r.problem) + ", t_end = " + number_text(r.t_end);
  return draw_figure(renderer, [&] { return render::work_precision_scene(result, title, width, height); });
}

std::vector<unsigned char> render_residuals(json request, const Limits& limits, render::Renderer& renderer,
                                            const RenderHooks& hooks) {
  if (!request.is_object()) throw FieldError("invalid_field", "", "the request must be a JSON object");
  const int width = take_int(request, "width", kResidualsFigure.width, false);
  const int height = take_int(request, "height", kResidualsFigure.height, false);
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
  before_work(hooks);
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
  const std::string title = "\u2016f(y\u2099)\u2016 against solver CPU time: " + std::string(to_string(base.problem.kind)) + " on " +
                            group_name(base.problem) + ", h = " + number_text(base.h);
  return draw_figure(renderer, [&] { return render::residuals_scene(runs, title, width, height); });
}

}  // namespace lienewton::service
