#include "problem_spec.hpp"

#include <atomic>

#include "group_registry.hpp"
#include "problems.hpp"
#include "validation.hpp"

namespace lienewton {

Eigen::MatrixXd ProblemSpec::start() const {
  if (z) return *z;
  if (is(ProblemKind::heavy_top)) return HeavyTop{heavy_top}.start();
  if (is(ProblemKind::stiff_body)) return StiffBody{stiff_body}.start();
  if (is(ProblemKind::chain)) return Chain{chain}.start(n);
  return resolved->seeded_start(family(), n, seed);
}

namespace {
std::atomic<std::uint64_t> validations{0};
}  // namespace

std::uint64_t problem_validations() { return validations.load(); }

void validate(const ProblemSpec& problem, int threads) {
  validations.fetch_add(1);
  fields::check_bounds(problem);  // n
  validation::check_problem_domain(problem);
  validation::check_rigid_body(problem.rigid_body);
  validation::check_heavy_top(problem);
  validation::check_stiff_body(problem);
  validation::check_chain(problem);
  validation::check_start_point(problem);
  validation::check_user_field(problem, threads);
}

std::shared_ptr<const user_field::Program> ProblemSpec::program() const {
  return programs->get(*g, family().program_size(n), parameters);
}

std::string ProblemSpec::name() const { return g ? "g(y)" : std::string(to_string(kind)); }

}  // namespace lienewton
