// The solvers on (SE(3) x R^6)^k, compiled once (rotation_instances.hpp says why).
#include "rotation_instances.hpp"

namespace lienewton {
LIENEWTON_SOLVERS_ON(, SE3xR6PowerGroup)
}  // namespace lienewton
