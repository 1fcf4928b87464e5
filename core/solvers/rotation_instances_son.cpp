// The solvers on SO(N), compiled once (rotation_instances.hpp says why).
#include "rotation_instances.hpp"

namespace lienewton {
LIENEWTON_SOLVERS_ON(, SONGroup)
}  // namespace lienewton
