// The solvers on R^n, compiled once for every test that solves on it (rn_group.hpp declares them).
#include "rn_group.hpp"

namespace lienewton {
LIENEWTON_SOLVERS_ON(, RnGroup)
}  // namespace lienewton
