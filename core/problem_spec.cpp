#include "problem_spec.hpp"

#include "start_point.hpp"
#include "validation.hpp"

namespace lienewton {

Eigen::MatrixXd ProblemSpec::start() const { return z ? *z : start_point(n, seed); }

void validate(const ProblemSpec& problem) {
  fields::check_bounds(problem);  // n
  validation::check_problem_dimension(problem.kind, problem.n);
  validation::check_rigid_body(problem.rigid_body);
  validation::check_start_point(problem.z, problem.n);
}

}  // namespace lienewton
