#include "problem_spec.hpp"

#include "group_registry.hpp"
#include "validation.hpp"

namespace lienewton {

Eigen::MatrixXd ProblemSpec::start() const { return z ? *z : group_family(group).random(n, seed); }

void validate(const ProblemSpec& problem) {
  fields::check_bounds(problem);  // n
  validation::check_problem_domain(problem);
  validation::check_rigid_body(problem.rigid_body);
  validation::check_start_point(problem);
}

}  // namespace lienewton
