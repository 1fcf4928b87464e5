#pragma once
// Ticks and labels of chart axes. A log axis ticks every decade (and 2, 5 between them when a decade is
// wide enough, 1..9 when not even two such ticks fall inside), labelling only as many as fit; a linear axis ticks at 1, 2 or 5
// times a power of ten.
#include <string>
#include <vector>

namespace lienewton::render {

enum class AxisUnit { plain, seconds };  // seconds: tick labels as "10 us", "1 ms", "1 s"

struct AxisTick {
  double value = 0;
  bool labelled = false;  // unlabelled ticks get a grid line only
};

// Ticks for a log axis from 10^log_lo to 10^log_hi drawn over pixels; labelled ticks are at least
// min_spacing pixels apart.
std::vector<AxisTick> log_ticks(double log_lo, double log_hi, float pixels, float min_spacing);
// Ticks for a linear axis from lo to hi, at least min_spacing pixels and min_step apart, all labelled.
std::vector<AxisTick> linear_ticks(double lo, double hi, float pixels, float min_spacing, double min_step = 0);

// "0.01", "100", "1e-08" -> "1e-8", "2e+06" -> "2e6"; with unit seconds "10 us", "1.5 ms", "2 s".
std::string tick_label(double value, AxisUnit unit);
// A step size as typeset: "2⁻³" where x is a power of two, else "%g" ("0.3").
std::string power_of_two_label(double x);

}  // namespace lienewton::render
