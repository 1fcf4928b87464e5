// The JSON names of the enums; one table per enum so the string and the value cannot drift apart.
#include <utility>

#include "options.hpp"
#include "status.hpp"

namespace lienewton {
namespace {

constexpr std::pair<Status, std::string_view> kStatusNames[] = {
    {Status::converged, "converged"},   {Status::max_iterations, "max_iterations"},
    {Status::diverged, "diverged"},     {Status::non_finite, "non_finite"},
    {Status::left_log_domain, "left_log_domain"}, {Status::singular_differential, "singular_differential"},
    {Status::stagnated, "stagnated"},   {Status::off_branch, "off_branch"},
    {Status::local_minimum, "local_minimum"},   {Status::no_descent, "no_descent"},
    {Status::cancelled, "cancelled"}};
constexpr std::pair<ProblemKind, std::string_view> kProblemNames[] = {
    {ProblemKind::paper_linear, "paper-linear"}, {ProblemKind::paper_sine, "paper-sine"},
    {ProblemKind::rigid_body, "rigid-body"}};
constexpr std::pair<Method, std::string_view> kMethodNames[] = {
    {Method::fixed_point, "fixed-point"}, {Method::newton_group, "newton-group"},
    {Method::newton_algebra, "newton-algebra"}};
constexpr std::pair<Differential, std::string_view> kDifferentialNames[] = {
    {Differential::finite_difference, "finite-difference"}, {Differential::dexpinv_0, "dexpinv-0"},
    {Differential::dexpinv_1, "dexpinv-1"}, {Differential::exact, "exact"}};
constexpr std::pair<Integrator, std::string_view> kIntegratorNames[] = {
    {Integrator::implicit_euler, "implicit-euler"}, {Integrator::dirk_cg2, "dirk-cg2"}};
constexpr std::pair<LinearSolver, std::string_view> kLinearSolverNames[] = {
    {LinearSolver::auto_select, "auto"}, {LinearSolver::lu, "lu"}, {LinearSolver::gmres, "gmres"}};
constexpr std::pair<Stopping, std::string_view> kStoppingNames[] = {
    {Stopping::residual, "residual"}, {Stopping::algebra_residual, "algebra-residual"}};
constexpr std::pair<Globalization, std::string_view> kGlobalizationNames[] = {
    {Globalization::none, "none"}, {Globalization::line_search, "line-search"},
    {Globalization::trust_region, "trust-region"}};
constexpr std::pair<Predictor, std::string_view> kPredictorNames[] = {
    {Predictor::none, "none"}, {Predictor::lie_euler, "lie-euler"}};
constexpr std::pair<StageStart, std::string_view> kStageStartNames[] = {
    {StageStart::given, "start"}, {StageStart::root, "root"}, {StageStart::identity, "identity"},
    {StageStart::restart, "restart"}};

template <class E, std::size_t K>
std::string_view name_of(const std::pair<E, std::string_view> (&table)[K], E value) {
  for (const auto& [e, name] : table)
    if (e == value) return name;
  return "unknown";
}
template <class E, std::size_t K>
std::optional<E> value_of(const std::pair<E, std::string_view> (&table)[K], std::string_view name) {
  for (const auto& [e, n] : table)
    if (n == name) return e;
  return std::nullopt;
}

}  // namespace

std::string_view to_string(Status v) { return name_of(kStatusNames, v); }
std::string_view to_string(ProblemKind v) { return name_of(kProblemNames, v); }
std::string_view to_string(Method v) { return name_of(kMethodNames, v); }
std::string_view to_string(Differential v) { return name_of(kDifferentialNames, v); }
std::string_view to_string(Integrator v) { return name_of(kIntegratorNames, v); }
std::string_view to_string(LinearSolver v) { return name_of(kLinearSolverNames, v); }
std::string_view to_string(Stopping v) { return name_of(kStoppingNames, v); }
std::string_view to_string(Globalization v) { return name_of(kGlobalizationNames, v); }
std::string_view to_string(Predictor v) { return name_of(kPredictorNames, v); }
std::string_view to_string(StageStart v) { return name_of(kStageStartNames, v); }
std::optional<Status> status_from_string(std::string_view s) { return value_of(kStatusNames, s); }
std::optional<ProblemKind> problem_from_string(std::string_view s) { return value_of(kProblemNames, s); }
std::optional<Method> method_from_string(std::string_view s) { return value_of(kMethodNames, s); }
std::optional<Differential> differential_from_string(std::string_view s) { return value_of(kDifferentialNames, s); }
std::optional<Integrator> integrator_from_string(std::string_view s) { return value_of(kIntegratorNames, s); }
std::optional<LinearSolver> linear_solver_from_string(std::string_view s) { return value_of(kLinearSolverNames, s); }
std::optional<Stopping> stopping_from_string(std::string_view s) { return value_of(kStoppingNames, s); }
std::optional<Globalization> globalization_from_string(std::string_view s) {
  return value_of(kGlobalizationNames, s);
}
std::optional<Predictor> predictor_from_string(std::string_view s) { return value_of(kPredictorNames, s); }

}  // namespace lienewton
