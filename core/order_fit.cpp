#include "order_fit.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numeric>

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

bool AsymptoticRange::contains(std::size_t i) const {
  return std::find(indices.begin(), indices.end(), i) != indices.end();
}

AsymptoticRange asymptotic_range(const std::vector<double>& h, const std::vector<double>& error) {
  std::vector<std::size_t> by_h;  // usable points, smallest h first
  for (std::size_t i = 0; i < h.size() && i < error.size(); ++i)
    if (std::isfinite(h[i]) && h[i] > 0 && std::isfinite(error[i]) && error[i] > 0) by_h.push_back(i);
  std::sort(by_h.begin(), by_h.end(), [&](std::size_t a, std::size_t b) { return h[a] < h[b]; });
  const auto slope = [&](std::size_t a, std::size_t b) {
    return std::log(error[b] / error[a]) / std::log(h[b] / h[a]);
  };
  AsymptoticRange range;
  std::size_t count = by_h.size();
  if (by_h.size() >= 3) {
    count = 2;
    const double reference = slope(by_h[0], by_h[1]);
    while (count < by_h.size() && std::abs(slope(by_h[count - 1], by_h[count]) - reference) <= kSlopeAgreement)
      ++count;
  }
  range.indices.assign(by_h.begin(), by_h.begin() + static_cast<std::ptrdiff_t>(count));
  std::vector<double> hs, es;
  for (std::size_t i : range.indices) hs.push_back(h[i]), es.push_back(error[i]);
  range.order = fitted_order(hs, es);
  return range;
}

}  // namespace lienewton
