#include "server/openapi_labels.hpp"

#include <string>

#include "core/options.hpp"
#include "core/solvers/newton_step.hpp"
#include "core/status.hpp"
#include "render/basin_scene.hpp"
#include "render/colormap.hpp"
#include "render/heatmap_scene.hpp"
#include "render/options.hpp"
#include "render/series_style.hpp"

namespace lienewton::service {
namespace {

using nlohmann::json;

// What a reader sees for one enum value. Each words() below switches without a default, so a new enum value
// without words fails to compile (-Wswitch under -Werror).
struct Words {
  const char* label;        // in a select or a legend
  const char* short_label;  // in a column head or a compact series name
  const char* description;  // one line, for a tooltip or a legend
};

Words words(ProblemKind p) {
  switch (p) {
    case ProblemKind::paper_linear: return {"paper-linear (\u00a75, linear g)", "paper-linear", "section 5: g(y) = diag(diag(y,1),1) − diag(diag(y,1),−1), linear in y"};
    case ProblemKind::paper_sine: return {"paper-sine (\u00a75, sine g)", "paper-sine", "section 5: g(y) = U − Uᵀ with U = sin.(y)(2y − 5y²)"};
    case ProblemKind::rigid_body: return {"rigid-body (free rigid body)", "rigid-body", "the free rigid body on SO(3) (inertia and momentum given)"};
  }
  return {};
}

Words words(Method m) {
  switch (m) {
    case Method::fixed_point: return {"Fixed point (1.2)", "Fixed point", "fixed-point iteration (1.2)"};
    case Method::newton_group: return {"Newton V1, group (3.5)", "Newton group", "Newton's method on the group, Version 1 (3.5)"};
    case Method::newton_algebra: return {"Newton V2, algebra (3.20)", "Newton algebra", "Newton's method in the algebra, Version 2 (3.20)"};
  }
  return {};
}

// Fixed point forms no Newton differential, so a differential choice means nothing for it.
bool uses_differential(Method m) { return m != Method::fixed_point; }

Words words(Differential d) {
  switch (d) {
    case Differential::finite_difference: return {"Finite differences", "FD", "finite-difference differential (3.18)"};
    case Differential::dexpinv_0: return {"dexp\u207b\u00b9 to order 0", "order 0", "dexp\u207b\u00b9 truncated after order 0 (3.10)/(3.11)"};
    case Differential::dexpinv_1: return {"dexp\u207b\u00b9 to order 1", "order 1", "dexp\u207b\u00b9 truncated after order 1 (3.10)/(3.11)"};
    case Differential::exact: return {"Exact dexp\u207b\u00b9", "exact", "the exact dexp\u207b\u00b9"};
  }
  return {};
}

Words words(Integrator i) {
  switch (i) {
    case Integrator::implicit_euler: return {"Implicit Euler", "Euler", "implicit Lie group Euler (1.1)"};
    case Integrator::dirk_cg2: return {"DIRK Crouch\u2013Grossman 2", "DIRK-CG2", "L-stable SDIRK in Crouch\u2013Grossman form (section 6)"};
  }
  return {};
}

Words words(LinearSolver s) {
  switch (s) {
    case LinearSolver::auto_select: {
      static const std::string text = "LU up to N = " + std::to_string(kKrylovThreshold) + ", GMRES above";
      return {"Automatic", "auto", text.c_str()};
    }
    case LinearSolver::lu: return {"Dense LU", "LU", "dense LU of the Newton system"};
    case LinearSolver::gmres: return {"GMRES", "GMRES", "matrix-free GMRES with the Eisenstat\u2013Walker forcing term"};
  }
  return {};
}

Words words(Globalization g) {
  switch (g) {
    case Globalization::none: return {"None (the paper's full steps)", "plain", "Newton's full step every iteration, as the paper"};
    case Globalization::line_search: return {"Line search (Armijo, LM fallback)", "line search", "Armijo backtracking on 1/2 ||f||^2, Levenberg-Marquardt when Newton's step is no descent"};
    case Globalization::trust_region: return {"Trust region (dogleg)", "trust region", "dogleg steps on 1/2 ||f + D s||^2 inside a radius"};
  }
  return {};
}

Words words(Status s) {
  switch (s) {
    case Status::converged: return {"converged", "converged", "converged: \u2016f(y)\u2016 \u2264 tol"};
    case Status::max_iterations: return {"max iterations", "max iter", "max iterations reached above tol"};
    case Status::diverged: return {"diverged", "diverged", "diverged: residual or step blew up"};
    case Status::non_finite: return {"non finite", "non-finite", "non-finite: NaN or Inf appeared"};
    case Status::left_log_domain: return {"left log domain", "log domain", "left the log domain (angle reached \u03c0)"};
    case Status::singular_differential: return {"singular differential", "singular", "singular Newton system"};
    case Status::stagnated: return {"stagnated", "stagnated", "stagnated at the rounding floor"};
    case Status::off_branch: return {"off branch", "off branch", "solved, but h g(y) beyond angle \u03c0 (off branch)"};
    case Status::local_minimum:
      return {"local minimum", "local min", "stationary point of \u00bd\u2016f\u2016\u00b2 that is no root (globalised)"};
    case Status::no_descent:
      return {"no descent", "no descent", "no step decreases \u00bd\u2016f\u2016\u00b2 (globalised; \u03c6 not smooth there)"};
    case Status::cancelled: return {"cancelled", "cancelled", "cancelled, not computed"};
  }
  return {};
}

Words words(render::HeatmapMetric m) {
  switch (m) {
    case render::HeatmapMetric::iterations: return {"Iterations", "iterations", "iterations to converge"};
    case render::HeatmapMetric::rate: return {"Convergence rate r", "rate", "observed convergence rate (needs 3 residuals)"};
    case render::HeatmapMetric::residual: return {"Final residual", "residual", "log10 of the final \u2016f(y)\u2016"};
  }
  return {};
}

std::string css(render::Color c) {
  return "rgb(" + std::to_string(c.r) + "," + std::to_string(c.g) + "," + std::to_string(c.b) + ")";
}

// Badges and legends show a converged result green; the heatmap colours converged cells by their metric.
constexpr render::Color kConvergedBadgeColor{27, 120, 55, 255};

std::string status_css(Status s) {
  return css(s == Status::converged ? kConvergedBadgeColor : render::status_color(s));
}

template <class Enum, std::size_t K>
json entries(const Enum (&all)[K]) {
  json list = json::array();
  for (Enum e : all) {
    const Words w = words(e);
    list.push_back({{"value", std::string(to_string(e))}, {"label", w.label}, {"short", w.short_label},
                    {"description", w.description}});
  }
  return list;
}

json viridis_stops() {
  constexpr int kStops = 256;
  json stops = json::array();
  for (int i = 0; i < kStops; ++i) {
    const render::Color c = render::viridis(static_cast<double>(i) / (kStops - 1));
    stops.push_back({c.r, c.g, c.b});
  }
  return stops;
}

// The PNG charts' series styles, so that the dashboard draws series i as the server does.
json series_styles() {
  json styles = json::array();
  for (std::size_t i = 0; i < render::kDistinctSeriesStyles; ++i) {
    const render::SeriesStyle s = render::series_style(i);
    styles.push_back({{"color", css(s.color)}, {"dash", std::string(to_string(s.dash))},
                      {"dash_pattern", render::dash_pattern(s.dash)}, {"marker", std::string(to_string(s.marker))}});
  }
  return styles;
}

// Root k of a basin map is drawn in entry k (mod the length); pixels mix in black up to basin_darkest with
// iterations, as the PNG does.
json basin_root_colors() {
  json colors = json::array();
  for (int k = 0; k < render::kDistinctRootColors; ++k) colors.push_back(css(render::root_color(k)));
  return colors;
}

}  // namespace

json openapi_labels() {
  json methods = entries(kAllMethods);
  for (std::size_t i = 0; i < std::size(kAllMethods); ++i) methods[i]["uses_differential"] = uses_differential(kAllMethods[i]);
  json statuses = entries(kAllStatuses);
  for (std::size_t i = 0; i < std::size(kAllStatuses); ++i) statuses[i]["color"] = status_css(kAllStatuses[i]);
  return {{"enums",
           {{"problem", entries(kAllProblems)},
            {"method", methods},
            {"differential", entries(kAllDifferentials)},
            {"integrator", entries(kAllIntegrators)},
            {"linear_solver", entries(kAllLinearSolvers)},
            {"globalization", entries(kAllGlobalizations)},
            {"status", statuses},
            {"heatmap_metric", entries(render::kAllHeatmapMetrics)}}},
          {"colors", {{"no_value", css(render::kNoValueColor)}, {"viridis", viridis_stops()},
                      {"basin_roots", basin_root_colors()}, {"basin_darkest", render::kBasinDarkest},
                      {"rate_range", {render::kRateColorLo, render::kRateColorHi}},
                      {"rate_outlier_dot", css(render::kOutlierDotColor)}}},
          {"series_styles", series_styles()}};
}

}  // namespace lienewton::service
