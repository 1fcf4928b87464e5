#pragma once
// The paper's random start point y(0) = qr(rand(N, N)), SO(N)'s seeded element (groups/rotation_facts.hpp),
// reproducibly:
//   rng = std::mt19937_64(seed); A(i, j) = (rng() >> 11) * 2^-53 filled column by column (MATLAB order);
//   z = Q of Eigen's HouseholderQR(A) (Householder reflections, no sign normalisation), so det z = (-1)^N
//   possibly times -1: z lies in O(N), as in the paper.
#include <Eigen/Dense>
#include <cstdint>

namespace lienewton {
Eigen::MatrixXd start_point(int n, std::uint64_t seed);
}
