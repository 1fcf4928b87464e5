// The solvers on SE(3), compiled once (rotation_instances.hpp says why).
#include "rotation_instances.hpp"

namespace lienewton {
LIENEWTON_SOLVERS_ON(, SE3Group)
}  // namespace lienewton
