#include "render/log_axis.hpp"

#include <cmath>
#include <algorithm>
#include <cstdio>

namespace lienewton::render {
namespace {

constexpr double kSlack = 1e-9;  // ticks at the very ends count as inside

bool inside(double l, double lo, double hi) { return l >= lo - kSlack && l <= hi + kSlack; }

// Ticks at m * 10^e for the given mantissas; labelled when m == 1 and e is a multiple of every.
std::vector<AxisTick> decade_ticks(double log_lo, double log_hi, std::initializer_list<double> mantissas,
                                   int every, bool label_all) {
  std::vector<AxisTick> ticks;
  for (int e = static_cast<int>(std::floor(log_lo)); e <= static_cast<int>(std::ceil(log_hi)); ++e) {
    for (double m : mantissas) {
      if (!inside(e + std::log10(m), log_lo, log_hi)) continue;
      const bool labelled = label_all || (m == 1.0 && e % every == 0);
      ticks.push_back({m * std::pow(10.0, e), labelled});
    }
  }
  return ticks;
}

// "1e-08" -> "1e-8", "1e+06" -> "1e6": printf's exponent padding only takes room.
std::string trim_exponent(std::string s) {
  const auto e = s.find('e');
  if (e == std::string::npos) return s;
  std::string mantissa = s.substr(0, e), exponent = s.substr(e + 1);
  const bool negative = exponent[0] == '-';
  std::size_t first = (exponent[0] == '-' || exponent[0] == '+') ? 1 : 0;
  while (first + 1 < exponent.size() && exponent[first] == '0') ++first;
  return mantissa + "e" + (negative ? "-" : "") + exponent.substr(first);
}

}  // namespace

std::vector<AxisTick> log_ticks(double log_lo, double log_hi, float pixels, float min_spacing) {
  const double decades = log_hi - log_lo;
  const double per_decade = pixels / std::max(decades, 1e-9);
  if (per_decade >= 3 * min_spacing) {  // room for 1, 2 and 5 in every decade
    auto ticks = decade_ticks(log_lo, log_hi, {1, 2, 5}, 1, true);
    if (ticks.size() >= 2) return ticks;
    return decade_ticks(log_lo, log_hi, {1, 2, 3, 4, 5, 6, 7, 8, 9}, 1, true);
  }
  int every = 1;
  for (int k : {1, 2, 3, 5, 10, 20, 50, 100}) {
    every = k;
    if (per_decade * k >= min_spacing) break;
  }
  auto ticks = decade_ticks(log_lo, log_hi, {1}, every, false);
  if (ticks.empty()) ticks = decade_ticks(log_lo, log_hi, {1, 2, 3, 4, 5, 6, 7, 8, 9}, 1, true);
  return ticks;
}

std::vector<AxisTick> linear_ticks(double lo, double hi, float pixels, float min_spacing, double min_step) {
  const double span = hi - lo;
  if (!(span > 0)) return {{lo, true}};
  const double max_ticks = std::max(1.0, std::floor(static_cast<double>(pixels) / min_spacing));
  const double raw = std::max(span / max_ticks, min_step);
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  double step = 10 * power;
  for (double m : {1.0, 2.0, 5.0}) {
    if (m * power >= raw * (1 - kSlack)) {
      step = m * power;
      break;
    }
  }
  std::vector<AxisTick> ticks;
  for (double k = std::ceil(lo / step - kSlack); k * step <= hi + kSlack * step; ++k) {
    ticks.push_back({k * step + 0.0, true});  // + 0.0 turns -0 into 0
  }
  return ticks;
}

std::string power_of_two_label(double x) {
  const double k = std::log2(x);
  if (!(x > 0) || k != std::round(k) || std::abs(k) > 99) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", x);
    return text;
  }
  static constexpr const char* kDigits[] = {"\u2070", "\u00b9", "\u00b2", "\u00b3", "\u2074",
                                            "\u2075", "\u2076", "\u2077", "\u2078", "\u2079"};
  std::string out = k < 0 ? "2\u207b" : "2";
  for (char d : std::to_string(static_cast<int>(std::abs(k)))) out += kDigits[d - '0'];
  return out;
}

std::string tick_label(double value, AxisUnit unit) {
  char text[32];
  if (unit == AxisUnit::seconds && value != 0) {
    static constexpr struct {
      double scale;
      const char* suffix;
    } kUnits[] = {{1.0, "s"}, {1e-3, "ms"}, {1e-6, "\u00b5s"}, {1e-9, "ns"}};
    for (const auto& u : kUnits) {
      if (std::fabs(value) >= u.scale * (1 - 1e-9) || u.scale == 1e-9) {
        std::snprintf(text, sizeof text, "%g %s", value / u.scale, u.suffix);
        return text;
      }
    }
  }
  std::snprintf(text, sizeof text, "%g", value);
  return trim_exponent(text);
}

}  // namespace lienewton::render
