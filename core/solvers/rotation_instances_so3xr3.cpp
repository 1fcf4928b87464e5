// The solvers on SO(3) x R^3, compiled once (rotation_instances.hpp says why).
#include "rotation_instances.hpp"

namespace lienewton {
LIENEWTON_SOLVERS_ON(, SO3xR3Group)
}  // namespace lienewton
