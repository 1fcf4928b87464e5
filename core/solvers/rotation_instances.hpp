#pragma once
// The solvers on the service's groups are compiled once each, in rotation_instances_<group>.cpp (so3, son, se3,
// so3xr3, se3xr6), and every other file links to them: one group's instance of the three methods with every
// differential and globalization costs about two minutes of compiler time in the sanitizer build, and each file
// that solved on SO(3) and SO(N) (core, server, tests, benchmarks) used to compile its own.
// run_method.hpp includes this at its end, so whoever can call a solver sees these declarations.
#include "core/groups/mechanics_groups.hpp"
#include "core/groups/se3_group.hpp"
#include "core/groups/so3_group.hpp"
#include "core/groups/son_group.hpp"
#include "run_method.hpp"

// kind: `extern` for the declarations here, empty for the definitions in the .cpp files.
#define LIENEWTON_SOLVERS_ON(kind, G)                                                                        \
  kind template SolveResult fixed_point<G>(const Equation<G>&, const SolverOptions&, const TraceCallback&);    \
  kind template SolveResult newton_group<G>(const Equation<G>&, const SolverOptions&, const TraceCallback&);   \
  kind template SolveResult newton_algebra<G>(const Equation<G>&, const SolverOptions&, const TraceCallback&); \
  kind template SolveResult run_method<G>(Method, const Equation<G>&, const SolverOptions&, const TraceCallback&); \
  kind template SolveResult continued_root<G>(Method, const Equation<G>&, const SolverOptions&, const TraceCallback&, FirstTry);

namespace lienewton {
LIENEWTON_SOLVERS_ON(extern, SO3Group)
LIENEWTON_SOLVERS_ON(extern, SONGroup)
LIENEWTON_SOLVERS_ON(extern, SE3Group)
LIENEWTON_SOLVERS_ON(extern, SO3xR3Group)
LIENEWTON_SOLVERS_ON(extern, SE3xR6Group)
LIENEWTON_SOLVERS_ON(extern, SE3xR6PowerGroup)
}  // namespace lienewton
