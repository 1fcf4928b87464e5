#pragma once
// The request contract, written once: one row per request field (name, JSON type, bounds or enum, default,
// description, the routes that take it and the struct member it lands in), in request_fields()'s table
// (fields.cpp; the render routes' picture options in server/render_requests.cpp). The codec reads and refuses
// fields by these rows, core validation checks their bounds (check_bounds), /openapi.json is generated from them
// and the dashboard's forms read their defaults, limits and hints from /openapi.json. A new field is one row in
// the table plus its struct member.
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "options.hpp"
#include "heavy_top_params.hpp"
#include "rigid_body_params.hpp"
#include "shard.hpp"
#include "stiff_body_params.hpp"
#include "chain_params.hpp"
#include "user_field/program.hpp"

namespace lienewton {
struct ProblemSpec;
struct SolverOptions;
struct SolveRequest;
struct SweepRequest;
struct IntegrateRequest;
struct WorkPrecisionRequest;
struct WorkPrecisionChoice;
struct BasinRequest;
}  // namespace lienewton

namespace lienewton::fields {

inline constexpr double kNoDefault = std::numeric_limits<double>::quiet_NaN();

// The bounds core validation checks (validation::check) as well as the codec.
struct NumberField {
  const char* name;
  double min;
  double max;
  bool min_exclusive;  // (min, max] instead of [min, max]
  double default_value;  // kNoDefault when the field has none
  const char* description;

  bool contains(double x) const { return (min_exclusive ? x > min : x >= min) && x <= max; }  // false for NaN
  std::string range_text() const;  // "(0, 1e6]"
  // "<path> must be a finite number in (0, 1e6]"; path is name, or e.g. "cells[3].h" inside an array.
  std::string message(const std::string& path) const;
};

struct IntegerField {
  const char* name;
  long long min;
  long long max;  // the core's bound; a server may cap it lower (--max-n, --max-iterations)
  long long default_value;
  const char* description;

  bool contains(long long x) const { return x >= min && x <= max; }
  // "<path> must be an integer in [min, cap]", cap = min(max, server cap).
  std::string message(const std::string& path, long long cap = std::numeric_limits<long long>::max()) const;
};

inline constexpr NumberField h{"h", 0.0, 1e6, true, kNoDefault,
                               "step size (integrate: the first step tried when adaptive; absent, 0.1 or less as "
                               "the field's time scale asks, docs/integrators.md)"};
inline constexpr NumberField tol{"tol", 1e-16, 1.0, false, 1e-13, "absolute tolerance on ||f||"};
inline constexpr NumberField t_end{"t_end", 0.0, 1e9, true, 1.0, "end time (capped by --max-t-end)"};
inline constexpr IntegerField n{"n", 2, 100000, 3, "matrix size N (capped by --max-n)"};  // 1e5: beyond any memory
inline constexpr IntegerField max_iterations{"max_iterations", 1, 100000, 100, "capped by --max-iterations"};
inline constexpr IntegerField multistart{"multistart", 0, 10000, 0,
                                        "solves at h from seeded starts when no root was found before"};

// The tolerances of adaptive steps: the codec reads any finite number, core validation refuses one outside
// (0, 1] with 422 (validation::check_tolerance).
inline constexpr NumberField rtol{"rtol", 0.0, 1.0, true, kNoDefault,
                                  "relative tolerance of adaptive steps: with rtol or atol (the other then takes the "
                                  "same value) integrate chooses its step sizes by step doubling and h is the first "
                                  "step tried"};
inline constexpr NumberField atol{"atol", 0.0, 1.0, true, kNoDefault, "absolute tolerance of adaptive steps"};
inline constexpr NumberField tolerances{"tolerances", 0.0, 1.0, true, kNoDefault,
                                        "work-precision against tolerance: each choice runs with adaptive steps at "
                                        "rtol = atol = each of these (instead of the fixed steps h)"};
inline constexpr IntegerField max_steps{"max_steps", 1, 100000, 100000,
                                        "adaptive steps: the most steps, accepted and rejected, one integration takes"};

inline constexpr const NumberField* kNumberFields[] = {&h, &tol, &t_end};
inline constexpr const IntegerField* kIntegerFields[] = {&n, &max_iterations, &multistart};

// A bound as a person writes it: 1e6, 1e-16, 100, 0.5 (shortest round-trip, no "e+06").
std::string format_bound(double x);

// The routes of the API; a row's route set says which requests take it. The render routes take their base
// request's rows (frames: solve or integrate; heatmap: sweep; ...) plus their own picture rows.
enum Route : unsigned {
  solve = 1u << 0,  // POST /solve, its streams and the SSE GET, render/frames of a solve, render/residuals
  sweep = 1u << 1,
  basins = 1u << 2,
  integrate = 1u << 3,
  work_precision = 1u << 4,
  render_frames = 1u << 5,
  render_heatmap = 1u << 6,
  render_basins = 1u << 7,
  render_work_precision = 1u << 8,
  render_residuals = 1u << 9,
  render_invariants = 1u << 10,
  render_motion = 1u << 11,
};
using Routes = unsigned;
inline constexpr Routes kSolveLike = solve | basins | integrate | work_precision;  // one equation of size n
inline constexpr Routes kProblemRoutes = kSolveLike | sweep;                    // every route that takes a problem

enum class Type { number, integer, boolean, string, object, matrix };  // matrix: an array of rows of numbers

// A limit the server puts on top of the row's bound (service::Limits); the CLI has none.
enum class Cap { none, n, iterations, threads, frames, grid_axis };

// Where a field lands: the struct member it is read into (a ProblemSpec or SolverOptions member lands in every
// route's request; a request struct's member only in that request).
using Member = std::variant<
    ProblemKind ProblemSpec::*, std::string ProblemSpec::*, int ProblemSpec::*, std::uint64_t ProblemSpec::*,
    std::optional<Eigen::MatrixXd> ProblemSpec::*, RigidBodyParams ProblemSpec::*,
    std::optional<std::string> ProblemSpec::*, user_field::Parameters ProblemSpec::*,
    Method SolverOptions::*, Differential SolverOptions::*, LinearSolver SolverOptions::*, Stopping SolverOptions::*,
    Globalization SolverOptions::*, double SolverOptions::*, int SolverOptions::*, bool SolverOptions::*,
    double SolveRequest::*, std::optional<Eigen::MatrixXd> SolveRequest::*,
    double IntegrateRequest::*, int IntegrateRequest::*, bool IntegrateRequest::*, Integrator IntegrateRequest::*, Predictor IntegrateRequest::*,
    std::optional<double> IntegrateRequest::*,
    double WorkPrecisionRequest::*, Predictor WorkPrecisionRequest::*, std::vector<double> WorkPrecisionRequest::*,
    std::vector<WorkPrecisionChoice> WorkPrecisionRequest::*,
    Integrator WorkPrecisionChoice::*, Method WorkPrecisionChoice::*, Differential WorkPrecisionChoice::*,
    std::vector<Method> SweepRequest::*, std::vector<int> SweepRequest::*, std::vector<double> SweepRequest::*,
    int SweepRequest::*, std::optional<Shard> SweepRequest::*,
    std::vector<Method> BasinRequest::*, int BasinRequest::*, std::optional<double> BasinRequest::*,
    std::optional<Eigen::VectorXd> BasinRequest::*, std::optional<Shard> BasinRequest::*,
    Eigen::Vector3d RigidBodyParams::*, int Shard::*, HeavyTopParams ProblemSpec::*, double HeavyTopParams::*,
    Eigen::Vector3d HeavyTopParams::*, Eigen::Matrix3d HeavyTopParams::*, StiffBodyParams ProblemSpec::*,
    double StiffBodyParams::*, std::optional<double> StiffBodyParams::*, Eigen::Vector3d StiffBodyParams::*,
    Eigen::Matrix3d StiffBodyParams::*, ChainParams ProblemSpec::*, double ChainParams::*,
    Eigen::Vector3d ChainParams::*>;

using Default = std::variant<std::monostate, double, long long, bool, std::string>;

struct Field {
  std::string name;
  Type type;                 // of the value, or of each element when array
  Routes routes = 0;
  std::vector<Member> lands{};  // empty: read by its route's own code (picture options)
  std::string description{};
  // number and integer: the codec's range (an integer's max may be capped by the server, cap)
  std::optional<double> minimum{}, maximum{};
  bool exclusive_minimum = false;
  Cap cap = Cap::none;
  bool publish_cap = false;                     // the schema's maximum is the server's default cap
  // The schema's bounds where they are not the codec's: a bound core validation refuses with 422.
  std::optional<double> schema_minimum{}, schema_maximum{};
  std::vector<std::string> values{};            // string: the enum
  Default default_value{};
  // array: [min_items, max_items] elements (max_items may be capped, cap_items), described as `items` in errors
  bool array = false;
  std::size_t min_items = 0, max_items = 0;
  Cap cap_items = Cap::none;
  std::string items{};
  // object: the named schema it is published as (RigidBody, HeavyTop, StiffBody, Chain)
  std::string schema{};
  std::vector<Field> properties{};              // object: its fields
  std::vector<std::string> required{};          // object: the fields it needs

  bool takes(Route route) const { return (routes & route) != 0; }
  // Whether x is within [minimum, maximum] ((minimum, maximum] when exclusive_minimum); an absent bound holds.
  bool contains(double x) const {
    return (!minimum || (exclusive_minimum ? x > *minimum : x >= *minimum)) && (!maximum || x <= *maximum);
  }
  // The message of a number outside [minimum, maximum] (or an integer outside [minimum, cap]), as the core's
  // NumberField/IntegerField words it.
  std::string number_message(const std::string& path) const;
  std::string integer_message(const std::string& path, long long cap) const;
};

// Every request field, in the order the codec reads them (an earlier field's error is the one reported).
const std::vector<Field>& request_fields();
// The fields one route takes, in reading order.
std::vector<const Field*> fields_of(Route route);
// The row of `name` that `route` takes; nullptr when it takes none.
const Field* find(Route route, std::string_view name);

// Checks each bounded number and integer of the rows that land in `object` (a ProblemSpec or SolverOptions), in
// the table's order; throws RequestError (invalid) naming the first one out of its row's bounds.
template <class C>
void check_bounds(const C& object);

// An enum's names in API order, for the rows' enums and the codec's messages.
template <class E, std::size_t K>
std::vector<std::string> names(const E (&all)[K]) {
  std::vector<std::string> out;
  for (E e : all) out.emplace_back(to_string(e));
  return out;
}

}  // namespace lienewton::fields
