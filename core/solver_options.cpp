#include "solver_options.hpp"

#include "validation.hpp"

namespace lienewton {

void validate(const SolverOptions& options) {
  validation::check(fields::tol, options.tol, "tol");
  validation::check(fields::max_iterations, options.max_iterations, "max_iterations");
}

}  // namespace lienewton
