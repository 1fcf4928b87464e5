#pragma once
// The observed order of an integrator: the least-squares slope p of log(error) against log(h), as a
// work-precision diagram shows it (error ~ C h^p in the asymptotic range).
#include <optional>
#include <vector>

namespace lienewton {

// Points whose h or error is not finite and positive are left out (a zero error has no logarithm).
// Nothing when fewer than two points with distinct h remain.
std::optional<double> fitted_order(const std::vector<double>& h, const std::vector<double>& error);

}  // namespace lienewton
