#include "order_fit.hpp"

#include <cmath>
#include <cstddef>

namespace lienewton {

std::optional<double> fitted_order(const std::vector<double>& h, const std::vector<double>& error) {
  std::vector<double> x, y;
  for (std::size_t i = 0; i < h.size() && i < error.size(); ++i) {
    const bool usable = std::isfinite(h[i]) && h[i] > 0 && std::isfinite(error[i]) && error[i] > 0;
    if (!usable) continue;
    x.push_back(std::log(h[i]));
    y.push_back(std::log(error[i]));
  }
  if (x.size() < 2) return std::nullopt;
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < x.size(); ++i) mx += x[i], my += y[i];
  mx /= static_cast<double>(x.size());
  my /= static_cast<double>(y.size());
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxy += (x[i] - mx) * (y[i] - my);
    sxx += (x[i] - mx) * (x[i] - mx);
  }
  if (!(sxx > 0)) return std::nullopt;  // all h equal: no slope
  return sxy / sxx;
}

}  // namespace lienewton
