#pragma once
// Random algebra coordinates for the group property tests, drawn the same way in every fixture.
#include <random>

#include "core/groups/lie_group.hpp"

namespace lienewton::test {

// A unit vector in a uniformly random direction of the algebra (normalised Gaussian coordinates).
template <class G>
typename G::Vector random_direction(const G& g, std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  typename G::Vector v = zero_vector(g);
  for (int i = 0; i < g.dim(); ++i) v(i) = normal(rng);
  return v / v.norm();
}

// A random vector of norm in (lo, hi): on SO(N) every rotation angle of it is at most its norm.
template <class G>
typename G::Vector random_vector(const G& g, std::mt19937_64& rng, double lo, double hi) {
  std::uniform_real_distribution<double> r(lo, hi);
  return r(rng) * random_direction(g, rng);
}

}  // namespace lienewton::test
