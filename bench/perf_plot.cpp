// lienewton-perf-plot: reads Google Benchmark JSON from lienewton-bench (PerIteration/<differential>/N and
// LargeN_Solve/gmres/N, with the per_iteration counter) and draws time per Newton iteration vs N on log-log axes with the project's renderer.
//   lienewton-perf-plot bench.json docs/time_per_iteration.png [min_n_for_fit = 16]
// Uses the "median" aggregate when the run has repetitions, else the plain iteration entries. Prints, per
// differential, the least-squares slope of log(time per iteration) against log N over N >= min_n_for_fit, and
// separately over the lu (N <= 40) and gmres (N > 40) parts of that range.
#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "render/line_chart_scene.hpp"

namespace {

struct Series {
  std::map<int, double> seconds_per_iteration;  // by N
};

// log-log least-squares slope over the points with min_n <= N <= max_n.
double fitted_exponent(const Series& s, int min_n, int max_n = 1 << 30) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int k = 0;
  for (const auto& [n, t] : s.seconds_per_iteration) {
    if (n < min_n || n > max_n) continue;
    const double x = std::log(n), y = std::log(t);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
    ++k;
  }
  if (k < 2) return std::nan("");
  return (k * sxy - sx * sy) / (k * sxx - sx * sx);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3 || argc > 4) {
    std::fprintf(stderr, "usage: %s bench.json out.png [min_n_for_fit = 16]\n", argv[0]);
    return 2;
  }
  try {
    const int min_n = argc == 4 ? std::stoi(argv[3]) : 16;
    std::ifstream in(argv[1]);
    if (!in) throw std::runtime_error(std::string("cannot read ") + argv[1]);
    const nlohmann::json doc = nlohmann::json::parse(in);
    bool has_medians = false;
    for (const auto& b : doc.at("benchmarks")) has_medians |= b.value("aggregate_name", "") == "median";

    // Series: benchmark name prefix -> legend label. The auto choice per differential, and the exact
    // differential with GMRES forced at every N (where the crossover really is).
    const std::vector<std::pair<std::string, std::string>> kDifferentials = {
        {"PerIteration/exact/", "exact, auto (lu N <= 40, gmres above)"},
        {"PerIteration/fd/", "finite-difference, auto"},
        {"LargeN_Solve/gmres/", "exact, gmres forced"}};
    std::map<std::string, Series> series;
    for (const auto& b : doc.at("benchmarks")) {
      if (has_medians ? b.value("aggregate_name", "") != "median" : b.value("run_type", "") != "iteration") continue;
      if (b.contains("error_occurred") && b["error_occurred"].get<bool>()) continue;
      const std::string name = b.value("run_name", b.value("name", ""));
      for (const auto& [key, label] : kDifferentials) {
        const std::string& prefix = key;
        if (name.rfind(prefix, 0) != 0 || !b.contains("per_iteration")) continue;
        series[key].seconds_per_iteration[std::stoi(name.substr(prefix.size()))] = b["per_iteration"].get<double>();
      }
    }

    lienewton::render::LineChart chart;
    chart.title = "Newton Version 1, paper-linear, h = 2^-2: time per iteration";
    chart.x.label = "N (SO(N), q = N(N-1)/2 unknowns)";
    chart.y.label = "time / iteration";
    chart.y.unit = lienewton::render::AxisUnit::seconds;
    for (const auto& [key, label] : kDifferentials) {
      const auto it = series.find(key);
      if (it == series.end()) continue;
      lienewton::render::LineSeries s;
      const double slope = fitted_exponent(it->second, min_n);
      char text[128];
      std::snprintf(text, sizeof text, "%s: fit N >= %d ~ N^%.2f", label.c_str(), min_n, slope);
      s.label = text;
      s.style = lienewton::render::series_style(chart.series.size());
      for (const auto& [n, t] : it->second.seconds_per_iteration) {
        s.x.push_back(n);
        s.y.push_back(t);
        std::printf("%s N=%d per_iteration=%.6g s\n", label.c_str(), n, t);
      }
      std::printf("%s fitted exponent (N >= %d): %.3f\n", label.c_str(), min_n, slope);
      // Each side of N = 40 has its own slope too (the automatic choice once switched solver there; it now
      // switches at kKrylovThreshold).
      std::printf("%s fitted exponent (%d <= N <= 40): %.3f\n", label.c_str(), min_n,
                  fitted_exponent(it->second, min_n, 40));
      std::printf("%s fitted exponent (N > 40): %.3f\n", label.c_str(), fitted_exponent(it->second, 41));
      chart.series.push_back(std::move(s));
    }
    const std::vector<std::uint8_t> png = lienewton::render::line_chart_png(chart, 900, 600);
    std::ofstream out(argv[2], std::ios::binary);
    out.write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
    if (!out) throw std::runtime_error(std::string("cannot write ") + argv[2]);
    std::printf("wrote %s (%zu bytes)\n", argv[2], png.size());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lienewton-perf-plot: %s\n", e.what());
    return 1;
  }
}
