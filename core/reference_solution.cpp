#include "reference_solution.hpp"

#include "group_registry.hpp"

namespace lienewton {

ReferenceSolution reference_solution(const ProblemSpec& problem, const Eigen::MatrixXd& y0, double t_end) {
  return problem.family().reference_solution(problem, y0, t_end);
}

}  // namespace lienewton
