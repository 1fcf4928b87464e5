#include "server/openapi_labels.hpp"

#include <string>
#include <utility>

#include "core/integrators/methods.hpp"
#include "core/invariants.hpp"
#include "core/problems.hpp"
#include "core/vocabulary.hpp"
#include "render/basin_scene.hpp"
#include "render/colormap.hpp"
#include "render/heatmap_scene.hpp"
#include "render/options.hpp"
#include "render/series_style.hpp"
#include "server/output_limits.hpp"
#include "server/render_requests.hpp"

namespace lienewton::service {
namespace {

using nlohmann::json;

std::string css(render::Color c) {
  return "rgb(" + std::to_string(c.r) + "," + std::to_string(c.g) + "," + std::to_string(c.b) + ")";
}

// Badges and legends show a converged result green; the heatmap colours converged cells by their metric.
constexpr render::Color kConvergedBadgeColor{27, 120, 55, 255};

std::string status_css(Status s) {
  return css(s == Status::converged ? kConvergedBadgeColor : render::status_color(s));
}

// One enum's rows of the vocabulary, in the order of all; "explanation" only where a row has one.
template <class Enum, std::size_t K>
json entries(const Enum (&all)[K]) {
  json list = json::array();
  for (Enum e : all) {
    const Words w = words(e);
    json entry = {{"value", w.api}, {"label", w.label}, {"short", w.short_label}, {"description", w.sentence}};
    if (!w.explanation.empty()) entry["explanation"] = w.explanation;
    list.push_back(std::move(entry));
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

json openapi_labels(const ServerOptions& options) {
  json methods = entries(kAllMethods);
  for (std::size_t i = 0; i < std::size(kAllMethods); ++i) methods[i]["uses_differential"] = uses_differential(kAllMethods[i]);
  // rkmk4 is explicit: legends name no method for it. The order is what fitted orders are held to.
  json integrators = entries(kAllIntegrators);
  for (std::size_t i = 0; i < std::size(kAllIntegrators); ++i) {
    integrators[i]["solves_stages"] = solves_stages(kAllIntegrators[i]);
    integrators[i]["order"] = order_of(kAllIntegrators[i]);
  }
  // A problem's group and n when it has one (heavy-top: SOxR, n = 3) and the invariants its integrations report.
  json problems = entries(kAllProblems);
  for (std::size_t i = 0; i < std::size(kAllProblems); ++i) {
    if (const auto group = required_group(kAllProblems[i])) problems[i]["group"] = *group;
    if (const auto n = required_index(kAllProblems[i])) problems[i]["n"] = *n;
    json invariants = json::array();
    for (Invariant v : invariants_of(kAllProblems[i])) invariants.push_back(std::string(to_string(v)));
    problems[i]["invariants"] = std::move(invariants);
  }
  // Where each registered group draws bodies (motion, frames): "any" n, or the n that do (SO: 3).
  json groups = json::array();
  for (const std::string& name : registered_group_names()) {
    const std::optional<std::vector<int>> at = bodies_at(group_family(name));
    groups.push_back({{"value", name}, {"bodies_n", at ? json(*at) : json("any")}});
  }
  json statuses = entries(kAllStatuses);
  for (std::size_t i = 0; i < std::size(kAllStatuses); ++i) statuses[i]["color"] = status_css(kAllStatuses[i]);
  return {{"enums",
           {{"problem", problems},
            {"method", methods},
            {"differential", entries(kAllDifferentials)},
            {"integrator", integrators},
            {"linear_solver", entries(kAllLinearSolvers)},
            {"factorization", entries(kAllFactorizations)},
            {"globalization", entries(kAllGlobalizations)},
            {"stopping", entries(kAllStoppings)},
            {"predictor", entries(kAllPredictors)},
            {"branch", entries(kAllBranches)},
            {"found_by", entries(kAllSearches)},
            {"path_point", entries(kAllPathPointKinds)},
            {"invariant", entries(kAllInvariants)},
            {"status", statuses},
            {"heatmap_metric", entries(render::kAllHeatmapMetrics)}}},
          {"colors", {{"no_value", css(render::kNoValueColor)}, {"viridis", viridis_stops()},
                      {"basin_roots", basin_root_colors()}, {"basin_darkest", render::kBasinDarkest},
                      {"rate_range", {render::kRateColorLo, render::kRateColorHi}},
                      {"rate_outlier_dot", css(render::kOutlierDotColor)}}},
          {"groups", std::move(groups)},
          {"series_styles", series_styles()},
          // A basin map of k methods may have size^2 k basin_pixel_values <= max_values.
          {"output_limits", {{"max_values", options.output.max_values}, {"basin_pixel_values", kBasinPixelValues},
                             {"max_image_pixels", options.output.max_image_pixels},
                             {"max_grid_cells", options.limits.max_grid_cells},
                             {"request_seconds", options.request_timeout}, {"sweep_seconds", options.sweep_timeout}}}};
}

}  // namespace lienewton::service
