#include "solver_options.hpp"

#include "validation.hpp"

namespace lienewton {

void validate(const SolverOptions& options) {
  validation::check_tol(options.tol);
  validation::check_max_iterations(options.max_iterations);
}

}  // namespace lienewton
