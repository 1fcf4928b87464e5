// The solvers on the additive group of matrices, compiled once for the tests that use it (matrix_sum_group.hpp).
#include "matrix_sum_group.hpp"

namespace lienewton {
LIENEWTON_SOLVERS_ON(, MatrixSumGroup)
}  // namespace lienewton
