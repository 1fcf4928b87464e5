#pragma once
// The starts of continuation's last try, the restarts (continuation.hpp): y_k = y_0 exp(x_k), x_k a direction of
// the algebra drawn from the k-th restart's own generator, scaled so that exp(x_k) turns by at most
// kRestartAngle, the scale drawn uniformly. Each start depends on k alone (std::mt19937_64 is specified bit for
// bit, and its bits are mapped to [-1, 1) by hand: the standard's distributions are not portable), so a search
// finds the same roots on every machine, thread and rank count.
#include <cstdint>
#include <random>

#include "core/groups/lie_group.hpp"

namespace lienewton {

// The largest rotation angle of a restart's exp(x_k): inside log's branch around y_0, short of pi.
inline constexpr double kRestartAngle = 3.1;

template <LieGroup G>
typename G::Element restart_start(const G& g, const typename G::Element& y0, int k) {
  std::mt19937_64 rng(0x9e3779b97f4a7c15ULL + static_cast<std::uint64_t>(k));
  const auto uniform = [&rng] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };  // [0, 1)
  typename G::Vector x = zero_vector(g);
  for (int i = 0; i < g.dim(); ++i) x[i] = 2.0 * uniform() - 1.0;
  const double angle = g.angle(g.spectral(x));
  if (angle > 0) x *= uniform() * kRestartAngle / angle;
  return g.times_exp(y0, x);
}

}  // namespace lienewton
