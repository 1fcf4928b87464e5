#pragma once
// The additive group of real n x n matrices (rn_group.hpp), registered as "Rnxn" the way a real group is: this
// header and its one registry line below are all it takes for every request (solve, sweep, basins, integrate,
// work-precision) to run on it. Both Newton versions are classical Newton there, on f(y) = y - z - h g(y); its
// algebra holds the skew matrices, so the paper's two problems are defined on it. No production path names it.
#include "core/register_group.hpp"
#include "rn_group.hpp"

namespace lienewton {

using MatrixSumGroup = AdditiveGroup<Eigen::MatrixXd>;
static_assert(LieGroup<MatrixSumGroup>);

struct MatrixSumFamily {
  static constexpr const char* kName = "Rnxn";
  template <class F>
  static decltype(auto) with_group(int n, F&& f) {
    return f(MatrixSumGroup(n));
  }
};

// The solvers on it are compiled once, in matrix_sum_instances.cpp.
LIENEWTON_SOLVERS_ON(extern, MatrixSumGroup)

inline const bool kMatrixSumRegistered = register_group<MatrixSumFamily>();

}  // namespace lienewton
