#pragma once
// Continuation's search (core/solvers/continuation.hpp) with a scripted stage solver, for tests of the order in
// which it tries its paths: no stage is solved, so the path it takes depends on the script alone, not on rounding.
// The equation is paper-linear N = 5 at step h (seed 1: det z = +1, so the component identity is I).
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "core/groups/son_group.hpp"
#include "core/problems.hpp"
#include "core/solvers/continuation.hpp"
#include "core/start_point.hpp"

namespace lienewton {

struct ScriptedSearch {
  // The root a stage reaches from its equation's start at its h with its options, or nothing: the stage then fails
  // with max_iterations at its start.
  using Root = std::optional<Eigen::MatrixXd>;
  using Script = std::function<Root(const Equation<SONGroup>&, const SolverOptions&)>;

  explicit ScriptedSearch(double h) : eq(Equation<SONGroup>::implicit_euler(g, z, h, *field)) {}

  SONGroup g{5};
  Eigen::MatrixXd z = start_point(5, 1);
  std::unique_ptr<VectorField<SONGroup>> field = make_field(g, ProblemKind::paper_linear, RigidBodyParams{});
  Equation<SONGroup> eq;
  std::vector<SolverOptions> seen;  // the options of every stage, in order

  SolveResult run(const SolverOptions& opt, const Script& script) {
    const TraceCallback none;
    return continued(eq, opt, none, [&](const Equation<SONGroup>& e, const SolverOptions& o, const TraceCallback&) {
      seen.push_back(o);
      SolveResult r;
      r.y = e.start();
      r.iterations = o.max_iterations;
      r.status = Status::max_iterations;
      if (const auto root = script(e, o)) {
        r.y = *root;
        r.status = Status::converged;
        r.iterations = 7;
      }
      return r;
    });
  }
};

}  // namespace lienewton
