#include "fields.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>

#include "basins.hpp"
#include "group_registry.hpp"
#include "integrate.hpp"
#include "solve.hpp"
#include "solvers/continuation.hpp"
#include "solvers/newton_step.hpp"
#include "solvers/multistart.hpp"
#include "solvers/watchdog.hpp"
#include "sweep.hpp"
#include "validation.hpp"
#include "vocabulary.hpp"
#include "work_precision.hpp"

namespace lienewton::fields {

std::string format_bound(double x) {
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, x);
  std::string s(buf, end);
  const auto e = s.find('e');
  if (e == std::string::npos) return s;
  std::string exponent = s.substr(e + 1);
  const bool negative = exponent.front() == '-';
  exponent.erase(0, exponent.find_first_not_of("+-0"));
  return s.substr(0, e + 1) + (negative ? "-" : "") + exponent;
}

std::string NumberField::range_text() const {
  return std::string(min_exclusive ? "(" : "[") + format_bound(min) + ", " + format_bound(max) + "]";
}

std::string NumberField::message(const std::string& path) const {
  return path + " must be a finite number in " + range_text();
}

std::string IntegerField::message(const std::string& path, long long cap) const {
  return path + " must be an integer in [" + std::to_string(min) + ", " + std::to_string(std::min(max, cap)) + "]";
}

std::string Field::number_message(const std::string& path) const {
  if (!minimum || !maximum) return path + " must be a finite number";  // its bounds are core validation's (422)
  return NumberField{name.c_str(), *minimum, *maximum, exclusive_minimum, kNoDefault, ""}.message(path);
}

std::string Field::integer_message(const std::string& path, long long cap) const {
  const auto bound = [](const std::optional<double>& b, long long fallback) {
    return b ? static_cast<long long>(*b) : fallback;
  };
  return IntegerField{name.c_str(), bound(minimum, std::numeric_limits<long long>::min()),
                      bound(maximum, std::numeric_limits<long long>::max()), 0, ""}
      .message(path, cap);
}

namespace {

// A row from the core's bounds.
Field number(const NumberField& f, Routes routes, std::vector<Member> lands) {
  Field row{.name = f.name, .type = Type::number, .routes = routes, .lands = std::move(lands),
            .description = f.description, .minimum = f.min, .maximum = f.max, .exclusive_minimum = f.min_exclusive};
  if (!std::isnan(f.default_value)) row.default_value = f.default_value;
  return row;
}

// A tolerance of adaptive steps: the codec reads any finite number; (0, 1] is core validation's (422), published
// as the schema's bounds.
Field tolerance(const NumberField& f, Routes routes, std::vector<Member> lands) {
  Field row = number(f, routes, std::move(lands));
  row.schema_minimum = row.minimum;
  row.schema_maximum = row.maximum;
  row.minimum.reset();
  row.maximum.reset();
  return row;
}

Field integer(const IntegerField& f, Routes routes, std::vector<Member> lands, Cap cap = Cap::none) {
  return Field{.name = f.name, .type = Type::integer, .routes = routes, .lands = std::move(lands),
               .description = f.description, .minimum = static_cast<double>(f.min),
               .maximum = static_cast<double>(f.max), .cap = cap, .default_value = f.default_value};
}

template <class E, std::size_t K>
Field enumeration(const char* name, const E (&all)[K], Routes routes, std::vector<Member> lands, std::string description,
                  Default default_value = {}) {
  return Field{.name = name, .type = Type::string, .routes = routes, .lands = std::move(lands),
               .description = std::move(description), .values = names(all), .default_value = std::move(default_value)};
}

// "name (its sentence); ..." for every value: a description that lists each choice from the vocabulary.
template <class E, std::size_t K>
std::string each_with_its_sentence(const E (&all)[K]) {
  std::string out;
  for (const E value : all) {
    const Words w = words(value);
    out += (out.empty() ? "" : "; ") + std::string(w.api) + " (" + std::string(w.sentence) + ")";
  }
  return out;
}

// An enum value's API name, as a row's default.
template <class E>
Default api_name(E value) {
  return std::string(to_string(value));
}

Field boolean(const char* name, Routes routes, Member lands, std::string description) {
  return Field{.name = name, .type = Type::boolean, .routes = routes, .lands = {lands},
               .description = std::move(description), .default_value = false};
}

// An array of the element `item` describes, with [min_items, max_items] elements called `items` in errors.
Field array(Field item, std::size_t min_items, std::size_t max_items, std::string items, Cap cap_items = Cap::none) {
  item.array = true;
  item.min_items = min_items;
  item.max_items = max_items;
  item.items = std::move(items);
  item.cap_items = cap_items;
  return item;
}

std::string text(int x) { return std::to_string(x); }

// Three numbers of a problem's parameters P (heavy-top's, stiff-body's, chain's): the codec reads finite numbers, core
// validation refuses the rest with 422 (the schema's bounds, P::kBound).
template <class P>
Field three_numbers(const char* name, Eigen::Vector3d P::*member, const std::string& description, bool positive) {
  Field f{.name = name, .type = Type::number, .lands = {member}, .description = description,
          .exclusive_minimum = positive, .schema_minimum = positive ? 0.0 : -P::kBound, .schema_maximum = P::kBound};
  f = array(f, 3, 3, "3 finite numbers");
  const Eigen::Vector3d value = P{}.*member;
  f.description += " (default [" + format_bound(value.x()) + ", " + format_bound(value.y()) + ", " +
                   format_bound(value.z()) + "])";
  return f;
}

std::vector<Field> build() {
  const std::string method_text = "solver: fixed-point (1.2), newton-group = Version 1, newton-algebra = Version 2";
  const std::string differential_text = "how the Newton differential is formed";
  const Field shard_index{.name = "index", .type = Type::integer, .lands = {&Shard::index},
                          .description = "this part, 0 <= index < count", .minimum = 0, .maximum = 1000000};
  const Field shard_count{.name = "count", .type = Type::integer, .lands = {&Shard::count},
                          .description = "parts of the grid or map (>= 1); a basin map's part computes the rows r "
                                         "with r % count == index",
                          .minimum = 1, .maximum = 1000000};
  Field z{.name = "z", .type = Type::matrix, .routes = solve | integrate | basins, .lands = {&ProblemSpec::z},
          .description = "the equation's z, N x N rows, orthogonal to 1e-10 (default: from seed; its size is N when "
                         "n is absent): the start point of a solve (unless y0), y(0) of an integration; a basin "
                         "map's starts move, z stays"};
  Field coordinates{.name = "b1", .type = Type::number, .routes = basins, .lands = {&BasinRequest::b1},
                    .description = "n(n-1)/2 coordinates in the algebra (basis E_ij - E_ji, i < j row-major); "
                                   "normalised before use"};
  coordinates.array = true;
  Field b2 = coordinates;
  b2.name = "b2";
  b2.lands = {&BasinRequest::b2};
  Field three{.name = "inertia", .type = Type::number, .lands = {&RigidBodyParams::inertia},
              .description = "principal moments (positive)", .minimum = 0.0, .exclusive_minimum = true};
  three = array(three, 3, 3, "3 positive finite numbers");
  Field momentum{.name = "momentum", .type = Type::number, .lands = {&RigidBodyParams::momentum},
                 .description = "spatial angular momentum"};
  momentum = array(momentum, 3, 3, "3 finite numbers");
  const HeavyTopParams top;
  Field top_mass{.name = "mass", .type = Type::number, .lands = {&HeavyTopParams::mass}, .description = "m",
                 .exclusive_minimum = true, .schema_minimum = 0.0, .schema_maximum = HeavyTopParams::kBound,
                 .default_value = top.mass};
  Field top_rotation{.name = "rotation", .type = Type::matrix, .lands = {&HeavyTopParams::rotation},
                     .description = "R(0), a 3 x 3 rotation (orthogonal to 1e-10, det +1; default the identity)"};
  const StiffBodyParams stiff;
  Field stiff_k{.name = "k", .type = Type::number, .lands = {&StiffBodyParams::k},
                .description = "spring constant (with c = k the damper's eigenvalues are about -k/J_i: the stiffness)",
                .exclusive_minimum = true, .schema_minimum = 0.0, .schema_maximum = StiffBodyParams::kBound,
                .default_value = stiff.k};
  Field stiff_c{.name = "c", .type = Type::number, .lands = {&StiffBodyParams::c},
                .description = "damping (default k)", .schema_minimum = 0.0,
                .schema_maximum = StiffBodyParams::kBound};
  Field stiff_rotation{.name = "rotation", .type = Type::matrix, .lands = {&StiffBodyParams::rotation},
                       .description = "R(0), a 3 x 3 rotation (orthogonal to 1e-10, det +1; default "
                                      "exp(hat([0.5, -0.3, 0.8])))"};
  const ChainParams chain;
  // One number of chain's parameters, its schema bounds [lo, kBound] ((lo, kBound] when positive) and default.
  const auto chain_number = [&](const char* name, double ChainParams::*member, const std::string& description,
                                double lo, bool positive) {
    return Field{.name = name, .type = Type::number, .lands = {member}, .description = description,
                 .exclusive_minimum = positive, .schema_minimum = lo,
                 .schema_maximum = lo < 0.0 ? -lo : ChainParams::kBound, .default_value = chain.*member};
  };
  Field seed{.name = "seed", .type = Type::integer, .routes = kProblemRoutes, .lands = {&ProblemSpec::seed},
             .description = "unsigned 64-bit seed of the random start point", .minimum = 0.0,
             .maximum = static_cast<double>(std::numeric_limits<std::uint64_t>::max()), .default_value = 1LL};
  Field basin_n = integer(n, basins, {&ProblemSpec::n}, Cap::n);
  basin_n.description = "matrix size N (at least 3: the plane needs two directions)";
  basin_n.default_value = {};
  basin_n.schema_minimum = 3;
  Field multistart_row = integer(multistart, kProblemRoutes, {&SolverOptions::multistart});
  multistart_row.schema_maximum = multistart_row.maximum;
  multistart_row.description =
      std::string(multistart.description) + " (by the plain solve or continuation): at most " +
      text(kMultistartIterations) + " iterations each, the requested globalization, from y0 exp(x_k), k = 0, 1, "
      "..., seeded by k alone, exp(x_k) turning by at most " + format_bound(kMultistartAngle) + " rad; the first "
      "that ends at a root (converged or stagnated) ends the search. Its root is branch other when continuation "
      "showed z's branch folds before h, else unchecked; found_by and multistart_start say where it came from";

  std::vector<Field> t;
  // A default is the request struct's own (what the codec leaves in place), so that /openapi.json states what the
  // server applies; where routes' structs differ, one row per default.
  t.push_back(enumeration("problem", kAllProblems, solve | sweep | basins, {&ProblemSpec::kind}, "test problem",
                          api_name(ProblemSpec{}.kind)));
  t.push_back(enumeration("problem", kAllProblems, integrate | work_precision, {&ProblemSpec::kind}, "test problem",
                          api_name(IntegrateRequest{}.problem.kind)));
  t.push_back(Field{.name = "g", .type = Type::string, .routes = kProblemRoutes, .lands = {&ProblemSpec::g},
                    .description = "your own field g(y) instead of problem (both: 422), in MATLAB notation: a program "
                                   "over the n x n matrix y (and t: the stage time in integrate and work-precision, 0 elsewhere; pi; the parameters), statements separated by ; "
                                   "or new lines, its value in g or the last expression, e.g. u = sin(y)*(2*y - "
                                   "5*y^2); g = u - u'. Exact derivatives by forward-mode differentiation. Errors: "
                                   "422 with line and column"});
  t.push_back(Field{.name = "parameters", .type = Type::object, .routes = kProblemRoutes,
                    .lands = {&ProblemSpec::parameters},
                    .description = "with g: named numbers and matrices the program reads, e.g. {\"J\": [[1,0,0],"
                                   "[0,2,0],[0,0,3]]} (a number, an array: a row, an array of rows: a matrix, a string: an expression of "
                                   "constants in g's notation, e.g. \"pi/4\" or \"0.1*eye(3)\")"});
  t.push_back(Field{.name = "group", .type = Type::string, .routes = kProblemRoutes, .lands = {&ProblemSpec::group},
                    .description = "the Lie group by its registered name; n is its index, as in SO(n). SO: SO(n), n x n "
                                   "orthogonal z; SE: SE(3) (n = 3), z the 4 x 4 [[R, p], [0, 1]], algebra coordinates "
                                   "(w, r), rotation vector first; SOxR: SO(3) x R^3 (n = 3), z the 7 x 7 block "
                                   "diagonal [[R, 0], [0, [[I, w], [0, 1]]]], coordinates (rotation vector, w); SExR: "
                                   "SE(3) x R^6 (n = 3), z the 11 x 11 [[T, 0], [0, [[I, v], [0, 1]]]], coordinates "
                                   "(w, r, v); SExR^k: (SE(3) x R^6)^k, k = n rigid bodies (n from 2 to 128, "
                                   "\"SExR^8\" is short for n = 8), z = diag(y1, ..., yk) of SExR's 11 x 11 blocks, "
                                   "coordinates body by body. The built-in problems are defined on SO, heavy-top and "
                                   "stiff-body on SOxR, chain on SExR^k, which a request naming no group takes; g "
                                   "(your own field) on every group",
                    .values = registered_group_names(), .default_value = std::string("SO")});
  t.push_back(integer(n, solve | integrate | work_precision, {&ProblemSpec::n}, Cap::n));
  t.push_back(basin_n);
  t.push_back(seed);
  t.push_back(z);
  t.push_back(Field{.name = "rigid_body", .type = Type::object, .routes = kProblemRoutes,
                    .lands = {&ProblemSpec::rigid_body}, .description = "rigid-body only: the body's parameters",
                    .schema = "RigidBody", .properties = {three, momentum}});
  t.push_back(Field{.name = "heavy_top", .type = Type::object, .routes = kProblemRoutes,
                    .lands = {&ProblemSpec::heavy_top},
                    .description = "heavy-top only: the top's parameters and its start (R(0), omega(0)), which "
                                   "replace z; absent ones keep their defaults",
                    .schema = "HeavyTop",
                    .properties = {top_mass,
                                   three_numbers("inertia", &HeavyTopParams::inertia,
                                                 "J_c: principal moments about the centre of mass (positive); the "
                                                 "equation takes the pivot's J_c + m(|chi|^2 I - chi chi^T)",
                                                 true),
                                   three_numbers("center", &HeavyTopParams::center,
                                                 "chi: the centre of mass in the body", false),
                                   three_numbers("gravity", &HeavyTopParams::gravity, "gamma: gravity in space", false),
                                   top_rotation,
                                   three_numbers("omega", &HeavyTopParams::omega, "omega(0): body angular velocity",
                                                 false)}});
  t.push_back(Field{.name = "stiff_body", .type = Type::object, .routes = kProblemRoutes,
                    .lands = {&ProblemSpec::stiff_body},
                    .description = "stiff-body only: the body's spring, damper, inertia and forcing, and its start "
                                   "(R(0), omega(0)), which replace z; absent ones keep their defaults",
                    .schema = "StiffBody",
                    .properties = {stiff_k, stiff_c,
                                   three_numbers("J", &StiffBodyParams::J, "principal moments (positive)", true),
                                   three_numbers("f", &StiffBodyParams::f,
                                                 "forcing amplitudes: f(t) = (f1 sin 2t, f2 cos t, f3)", false),
                                   stiff_rotation,
                                   three_numbers("omega", &StiffBodyParams::omega, "omega(0): body angular velocity",
                                                 false)}});
  t.push_back(Field{
      .name = "chain", .type = Type::object, .routes = kProblemRoutes, .lands = {&ProblemSpec::chain},
      .description = "chain only: the links' mass, inertia and length, the joints' spring and damper, gravity, and "
                     "the start's tilt (the chain straight and at rest, turned by tilt about x from hanging along "
                     "-z), which replaces z; absent ones keep their defaults. n is the number of links",
      .schema = "Chain",
      .properties = {chain_number("mass", &ChainParams::mass, "m: each link's mass", 0.0, true),
                     three_numbers("inertia", &ChainParams::inertia,
                                   "J: each link's principal moments about its centre (positive; its joints sit on "
                                   "its z axis)",
                                   true),
                     chain_number("length", &ChainParams::length, "L: joint to joint, the joints at (0, 0, +-L/2)",
                                  0.0, true),
                     chain_number("stiffness", &ChainParams::stiffness, "k_s: each joint's spring", 0.0, false),
                     chain_number("damping", &ChainParams::damping,
                                  "c: each joint's damper (the energy is an invariant at c = 0 only)", 0.0, false),
                     three_numbers("gravity", &ChainParams::gravity, "gamma: gravity in space", false),
                     chain_number("tilt", &ChainParams::tilt, "the start's angle about x from hanging down (rad)",
                                  -std::numbers::pi, false)}});
  t.push_back(enumeration("method", kAllMethods, solve | integrate, {&SolverOptions::method}, method_text,
                          api_name(SolverOptions{}.method)));
  t.push_back(enumeration("differential", kAllDifferentials, solve | integrate | basins, {&SolverOptions::differential},
                          differential_text, api_name(SolverOptions{}.differential)));
  t.push_back(enumeration("differential", kAllDifferentials, sweep, {&SolverOptions::differential}, differential_text,
                          api_name(SweepRequest{}.solver.differential)));
  t.push_back(number(tol, kProblemRoutes, {&SolverOptions::tol}));
  t.push_back(integer(max_iterations, kProblemRoutes, {&SolverOptions::max_iterations}, Cap::iterations));
  t.push_back(enumeration("linear_solver", kAllLinearSolvers, kProblemRoutes, {&SolverOptions::linear_solver},
                          "auto: dense LU up to N = " + text(kKrylovThreshold) + ", matrix-free GMRES above",
                          std::string("auto")));
  t.push_back(enumeration(
      "stopping", kAllStoppings, kProblemRoutes, {&SolverOptions::stopping},
      "stopping rule of Version 2 and the fixed point: residual stops on ||f(y_n)|| = ||log(z^-1 y_n) - h g(y_n)|| "
      "<= tol as in the paper's section 5; algebra-residual on ||f~(v_n)|| (3.21), the test Version 2 would normally "
      "use. Version 1 always uses ||f(y_n)||",
      std::string("residual")));
  t.push_back(enumeration(
      "globalization", kAllGlobalizations, kProblemRoutes, {&SolverOptions::globalization},
      "Newton only (422 for fixed-point): none = the paper's full steps; line-search = Armijo backtracking on "
      "1/2 ||f||^2 along y exp(alpha u) (Version 1) or v + alpha u (Version 2), Levenberg-Marquardt "
      "(D^T D + mu I) u = -D^T f when Newton's step fails; trust-region = dogleg on 1/2 ||f + D s||^2",
      std::string("none")));
  t.push_back(boolean(
      "continuation", kProblemRoutes, &SolverOptions::continuation,
      "the root continued from y = z at h = 0: pseudo-arclength continuation of the roots (v, h) of "
      "v - h g(z exp v) = 0 from (0, 0) (tangent predictor, Newton corrector on the bordered system, step-length "
      "control), ending with the method's solve at exactly h from the path's prediction; its root must be the one "
      "nearest the prediction (contracting Newton steps). Where the branch turns back in h before the requested h "
      "the answer is status fold with fold_h. The result's branch says which root y is, continuation lists the "
      "path's points (streams send each as a record with path_point)"));
  t.push_back(boolean(
      "watchdog", kProblemRoutes, &SolverOptions::watchdog,
      "globalised Version 1 only: where the full Newton step does not decrease 1/2 ||f||^2 (it jumps at log's cut), "
      "take it anyway, up to " + text(kWatchdogSteps) + " full steps until one falls below the Armijo bound of the "
      "iterate it started from, else go back there and take the globalised step; at most " +
      text(kWatchdogEpisodes) + " such episodes go back. Continuation's solves never use it"));
  t.push_back(multistart_row);
  t.push_back(boolean("include_iterates", solve, &SolverOptions::include_iterates,
                      "keep every iterate y_n in the trace (TraceRecord.y)"));
  Field solve_h = number(h, solve | basins, {&SolveRequest::h});
  solve_h.default_value = SolveRequest{}.h;
  t.push_back(solve_h);
  t.push_back(number(h, integrate, {&IntegrateRequest::h}));
  t.push_back(Field{.name = "y0", .type = Type::matrix, .routes = solve, .lands = {&SolveRequest::y0},
                    .description = "starting guess of the iteration (default: z, as the paper): N x N rows, "
                                   "orthogonal to 1e-10, in the component of z (det y0 = det z); z stays the "
                                   "equation's z"});
  t.push_back(number(t_end, integrate | work_precision, {&IntegrateRequest::t_end, &WorkPrecisionRequest::t_end}));
  t.push_back(enumeration("integrator", kAllIntegrators, integrate, {&IntegrateRequest::integrator},
                          "Lie group integrator: " + each_with_its_sentence(kAllIntegrators),
                          api_name(IntegrateRequest{}.integrator)));
  t.push_back(tolerance(rtol, integrate, {&IntegrateRequest::rtol}));
  t.push_back(tolerance(atol, integrate, {&IntegrateRequest::atol}));
  t.push_back(integer(max_steps, integrate, {&IntegrateRequest::max_steps}));
  t.push_back(Field{.name = "frames", .type = Type::integer, .routes = integrate, .lands = {&IntegrateRequest::frames},
                    .description = "evenly spaced states to return", .minimum = 0.0, .cap = Cap::frames});
  t.push_back(Field{.name = "reference", .type = Type::boolean, .routes = integrate,
                    .lands = {&IntegrateRequest::reference},
                    .description = "compute a reference solution of the problem and the run's global_error against "
                                   "it (reference_seconds: its cost); false: skip it, and global_error is null",
                    .default_value = IntegrateRequest{}.reference});
  t.push_back(enumeration("predictor", kAllPredictors, integrate | work_precision,
                          {&IntegrateRequest::predictor, &WorkPrecisionRequest::predictor},
                          "where each stage Y_i = Z_i exp(h a_ii g(Y_i)) starts: none = Z_i (the paper's y_0 = z); "
                          "lie-euler = Z_i exp(h a_ii g(Z_i)), residual O(h^2) instead of O(h), kept only when its "
                          "residual is the smaller",
                          std::string("lie-euler")));
  t.push_back(array(Field{.name = "choices", .type = Type::object, .routes = work_precision,
                          .lands = {&WorkPrecisionRequest::choices},
                          .description = "the (integrator, method, differential) runs, each at every h (default: "
                                         "every integrator with newton-group and the exact differential)",
                          .schema = "WorkPrecisionChoice",
                          .properties = {enumeration("integrator", kAllIntegrators, 0, {&WorkPrecisionChoice::integrator},
                                                     "Lie group integrator (as integrate's integrator)",
                                                     api_name(WorkPrecisionChoice{}.integrator)),
                                         enumeration("method", kAllMethods, 0, {&WorkPrecisionChoice::method}, method_text,
                                                     api_name(WorkPrecisionChoice{}.method)),
                                         enumeration("differential", kAllDifferentials, 0,
                                                     {&WorkPrecisionChoice::differential}, differential_text,
                                                     api_name(WorkPrecisionChoice{}.differential))}},
                    1, 64, "choice objects"));
  Field wp_h = number(h, work_precision, {&WorkPrecisionRequest::h});
  t.push_back(array(wp_h, 1, 64, "step sizes"));
  t.push_back(array(tolerance(tolerances, work_precision, {&WorkPrecisionRequest::tolerances}), 1, 64, "tolerances"));
  t.push_back(array(enumeration("methods", kAllMethods, sweep, {&SweepRequest::methods}, method_text), 1, 16,
                    "method names"));
  t.push_back(array(integer(n, sweep, {&SweepRequest::n}, Cap::n), 1, 100000, "integers", Cap::grid_axis));
  t.push_back(array(number(h, sweep, {&SweepRequest::h}), 1, 100000, "step sizes", Cap::grid_axis));
  t.push_back(Field{.name = "threads", .type = Type::integer, .routes = sweep, .lands = {&SweepRequest::threads},
                    .description = "threads of this sweep (0: all cores)", .minimum = 0.0, .cap = Cap::threads,
                    .publish_cap = true, .default_value = 0LL});
  t.push_back(array(enumeration("methods", kAllMethods, basins, {&BasinRequest::methods}, method_text), 1,
                    std::size(kAllMethods), "method names"));
  // Any size is read: the core refuses one beyond its largest map (422), the server's output cap with 413.
  t.push_back(Field{.name = "size", .type = Type::integer, .routes = basins, .lands = {&BasinRequest::size},
                    .description = "pixels per side: size x size starts per method (beyond " + text(kMaxBasinSize) +
                                   ": 422; beyond --max-output-values numbers: 413)",
                    .minimum = 1.0, .maximum = static_cast<double>(std::numeric_limits<int>::max()),
                    .schema_maximum = kMaxBasinSize, .default_value = static_cast<long long>(kDefaultBasinSize)});
  t.push_back(Field{.name = "shard", .type = Type::object, .routes = sweep | basins,
                    .lands = {&SweepRequest::shard, &BasinRequest::shard},
                    .description = "compute only this part (lienewton merge joins the parts)",
                    .properties = {shard_index, shard_count}, .required = {"index", "count"}});
  t.push_back(Field{.name = "r", .type = Type::number, .routes = basins, .lands = {&BasinRequest::radius},
                    .description = "(a, b) in [-r, r]^2; default: the group's log radius (its default here is SO's)",
                    .minimum = 0.0, .maximum = 100.0, .exclusive_minimum = true,
                    .default_value = ProblemSpec{}.family().log_radius()});
  t.push_back(coordinates);
  t.push_back(b2);
  return t;
}

}  // namespace

template <class C>
void check_bounds(const C& object) {
  for (const Field& row : request_fields()) {
    for (const Member& m : row.lands) {
      std::visit([&](auto member) {
        if constexpr (std::is_same_v<decltype(member), double C::*>) {
          if (!row.contains(object.*member)) validation::invalid(row.name, row.number_message(row.name));
        } else if constexpr (std::is_same_v<decltype(member), int C::*>) {
          if (!row.contains(object.*member))
            validation::invalid(row.name, row.integer_message(row.name, std::numeric_limits<long long>::max()));
        }
      }, m);
    }
  }
}

template void check_bounds(const ProblemSpec&);
template void check_bounds(const SolverOptions&);

const std::vector<Field>& request_fields() {
  static const std::vector<Field> table = build();
  return table;
}

std::vector<const Field*> fields_of(Route route) {
  std::vector<const Field*> out;
  for (const Field& f : request_fields())
    if (f.takes(route)) out.push_back(&f);
  return out;
}

const Field* find(Route route, std::string_view name) {
  for (const Field& f : request_fields())
    if (f.takes(route) && f.name == name) return &f;
  return nullptr;
}

}  // namespace lienewton::fields
