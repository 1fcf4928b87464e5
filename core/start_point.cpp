#include "start_point.hpp"

#include <random>

namespace lienewton {

Eigen::MatrixXd start_point(int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  Eigen::MatrixXd a(n, n);
  for (int j = 0; j < n; ++j)  // column by column, as MATLAB's rand(N, N)
    for (int i = 0; i < n; ++i) a(i, j) = static_cast<double>(rng() >> 11) * 0x1.0p-53;
  return Eigen::HouseholderQR<Eigen::MatrixXd>(a).householderQ();
}

}  // namespace lienewton
