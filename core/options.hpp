#pragma once
// The user-facing choices of a solve: problem, method, differential, integrator. Names match the JSON API.
#include <optional>
#include <span>
#include <string_view>

namespace lienewton {

enum class ProblemKind { paper_linear, paper_sine, rigid_body, heavy_top, stiff_body, chain };
// The conserved quantities a built-in problem reports along an integration (core/invariants.hpp).
enum class Invariant { energy, vertical_momentum, axial_spin };
// fixed-point (1.2); newton-group = Version 1 (3.5); newton-algebra = Version 2 (3.20)
enum class Method { fixed_point, newton_group, newton_algebra };
// The fixed point forms no Newton differential, so a differential choice means nothing for it.
inline constexpr bool uses_differential(Method m) { return m != Method::fixed_point; }
// finite-difference (3.18)/(3.19); dexpinv-0 (3.10)/(3.16); dexpinv-1 (3.11)/(3.17); exact (3.8)/(3.22)
enum class Differential { finite_difference, dexpinv_0, dexpinv_1, exact };
// The integrators: each one's tableau, order and form is its row in core/integrators/methods.cpp, its words its row in
// core/vocabulary.cpp.
enum class Integrator { implicit_euler, dirk_cg2, rkmk_gauss1, rkmk_gauss2, rkmk_gauss3, rkmk_radau2, rkmk_radau3,
                        rkmk4, dirk_cg3, rkmk_lobatto3c };
// How the Newton system is solved: auto picks lu below kKrylovThreshold (solvers/newton_step.hpp) and gmres above;
// lu assembles the q x q matrix and factors it; gmres applies the differential matrix-free.
enum class LinearSolver { auto_select, lu, gmres };
// The factorization a solve or an integration used for its Newton systems (reported as linear_solver).
enum class Factorization { dense_lu, sparse_lu, gmres };
// When Version 2 and the fixed point stop: residual = ||f(y_n)|| <= tol with f(y) = log(z^-1 y) - h g(y), as the
// paper measures every method in section 5; algebra-residual = ||f~(v_n)|| <= tol, the test Version 2 "would
// normally" use (3.21), blind to log's branch. Version 1 always stops on ||f(y_n)||.
enum class Stopping { residual, algebra_residual };
// How Version 1 (3.5) and Version 2 (3.20) reach a root from afar (core/solvers/globalization.hpp): none = the
// paper's full steps; line-search = Armijo backtracking on phi = 1/2 ||f||^2 with a Levenberg-Marquardt
// fallback; trust-region = dogleg on the model 1/2 ||f + D s||^2.
enum class Globalization { none, line_search, trust_region };
// Where an integrator's stage equation Y_i = Z_i exp(h a_ii g(Y_i)) (section 6) starts its Newton iteration:
// none = at Z_i, as the paper starts at y_0 = z; lie-euler = at the explicit Lie-Euler value Z_i exp(h a_ii g(Z_i)),
// whose residual h a_ii (g(Z_i) - g(Y)) is O(h^2) instead of O(h) (core/integrate.cpp).
enum class Predictor { none, lie_euler };
// Which root a result's y is (core/solvers/continuation.hpp): continued = the root reached by following z's branch
// of roots from h = 0 to h with no fold passed; other = known not to be that root (the branch folds before h, or
// the root lies elsewhere); unchecked = nothing was done that would tell.
enum class Branch { continued, other, unchecked };
// Which search produced a result's y: the method's plain solve from the request's start, continuation along z's
// branch, or one of the multistart's seeded starts (core/solvers/multistart.hpp).
enum class Search { plain, continuation, multistart };
// A point of continuation's path: a corrected point of the branch (path), the method's solve at the requested h
// (final), or the branch's turning point in h (fold).
enum class PathPointKind { path, final, fold };

std::string_view to_string(ProblemKind);
std::string_view to_string(Method);
std::string_view to_string(Differential);
std::string_view to_string(Integrator);
std::string_view to_string(LinearSolver);
std::string_view to_string(Factorization);
std::string_view to_string(Stopping);
std::string_view to_string(Globalization);
std::string_view to_string(Predictor);
std::string_view to_string(Branch);
std::string_view to_string(Search);
std::string_view to_string(PathPointKind);
std::string_view to_string(Invariant);
std::optional<Method> method_from_string(std::string_view);
std::optional<Differential> differential_from_string(std::string_view);

inline constexpr ProblemKind kAllProblems[] = {ProblemKind::paper_linear, ProblemKind::paper_sine,
                                               ProblemKind::rigid_body, ProblemKind::heavy_top,
                                               ProblemKind::stiff_body, ProblemKind::chain};
inline constexpr Invariant kAllInvariants[] = {Invariant::energy, Invariant::vertical_momentum, Invariant::axial_spin};
inline constexpr Method kAllMethods[] = {Method::fixed_point, Method::newton_group, Method::newton_algebra};
inline constexpr Differential kAllDifferentials[] = {Differential::finite_difference, Differential::dexpinv_0,
                                                     Differential::dexpinv_1, Differential::exact};
inline constexpr Integrator kAllIntegrators[] = {Integrator::implicit_euler, Integrator::dirk_cg2,
                                                 Integrator::rkmk_gauss1,    Integrator::rkmk_gauss2,
                                                 Integrator::rkmk_gauss3,    Integrator::rkmk_radau2,
                                                 Integrator::rkmk_radau3,    Integrator::rkmk4,
                                                 Integrator::dirk_cg3,       Integrator::rkmk_lobatto3c};
inline constexpr LinearSolver kAllLinearSolvers[] = {LinearSolver::auto_select, LinearSolver::lu, LinearSolver::gmres};
inline constexpr Factorization kAllFactorizations[] = {Factorization::dense_lu, Factorization::sparse_lu,
                                                       Factorization::gmres};
inline constexpr Stopping kAllStoppings[] = {Stopping::residual, Stopping::algebra_residual};
inline constexpr Globalization kAllGlobalizations[] = {Globalization::none, Globalization::line_search,
                                                       Globalization::trust_region};
inline constexpr Predictor kAllPredictors[] = {Predictor::none, Predictor::lie_euler};
inline constexpr Branch kAllBranches[] = {Branch::continued, Branch::other, Branch::unchecked};
inline constexpr Search kAllSearches[] = {Search::plain, Search::continuation, Search::multistart};
inline constexpr PathPointKind kAllPathPointKinds[] = {PathPointKind::path, PathPointKind::final, PathPointKind::fold};

}  // namespace lienewton
