#include "solver_options.hpp"

#include <string>

#include "validation.hpp"

namespace lienewton {

void validate(const SolverOptions& options) {
  fields::check_bounds(options);  // tol, max_iterations, multistart
}

void check_globalization(Method method, const SolverOptions& options) {
  if (method == Method::fixed_point && options.globalization != Globalization::none)
    validation::unprocessable("globalization", "globalization " + std::string(to_string(options.globalization)) +
                                                   " needs newton-group or newton-algebra, not fixed-point");
}

}  // namespace lienewton
