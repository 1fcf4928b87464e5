#pragma once
// The observed order of an integrator: the least-squares slope p of log(error) against log(h), as a
// work-precision diagram shows it (error ~ C h^p in the asymptotic range).
#include <optional>
#include <vector>

namespace lienewton {

// Points whose h or error is not finite and positive are left out (a zero error has no logarithm).
// Nothing when fewer than two points with distinct h remain.
std::optional<double> fitted_order(const std::vector<double>& h, const std::vector<double>& error);

// The asymptotic range of a series (h, error): the points of the smallest h whose consecutive local slopes
// d log(error) / d log(h) agree, within kSlopeAgreement, with the slope between the two smallest h; extended towards
// larger h while the next local slope does. At least two points (all of them when fewer than three).
inline constexpr double kSlopeAgreement = 0.1;
struct AsymptoticRange {
  std::vector<std::size_t> indices;  // into the given vectors
  std::optional<double> order;       // fitted_order over them
  bool contains(std::size_t i) const;
};
AsymptoticRange asymptotic_range(const std::vector<double>& h, const std::vector<double>& error);

}  // namespace lienewton
