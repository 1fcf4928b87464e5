#pragma once
// Multistart (request field "multistart": K): when the search so far found no root at h, up to K solves at h from
// seeded starts y_k = y_0 exp(x_k), x_k a direction of the algebra drawn from the k-th start's own generator,
// scaled so that exp(x_k) turns by at most kMultistartAngle, the scale drawn uniformly. It looks for *a* root:
// the first start whose solve ends at a root (converged, or stagnated at its rounding floor: a later start's lucky
// dip below tol at the same root would not make it more of a root) ends the search. Its root is labelled other
// when continuation showed that z's branch has no root at h, unchecked otherwise (a seeded start may land on z's
// root; only continuation tells). Each start depends on k alone (std::mt19937_64 is specified bit for bit, and its
// bits are mapped to [-1, 1) by hand: the standard's distributions are not portable), so a search finds the same
// roots on every machine, thread and rank count.
#include <algorithm>
#include <cstdint>
#include <random>
#include <string>

#include "core/cancellation.hpp"
#include "core/groups/lie_group.hpp"
#include "core/solver_options.hpp"
#include "equation.hpp"
#include "solve_result.hpp"

namespace lienewton {

// The largest rotation angle of a start's exp(x_k): inside log's branch around y_0, short of pi.
inline constexpr double kMultistartAngle = 3.1;
// Iterations of each start's solve: a start that has not found its root by then is abandoned.
inline constexpr int kMultistartIterations = 32;

template <LieGroup G>
typename G::Element multistart_start(const G& g, const typename G::Element& y0, int k) {
  std::mt19937_64 rng(0x9e3779b97f4a7c15ULL + static_cast<std::uint64_t>(k));
  const auto uniform = [&rng] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };  // [0, 1)
  typename G::Vector x = zero_vector(g);
  for (int i = 0; i < g.dim(); ++i) x[i] = 2.0 * uniform() - 1.0;
  const double angle = g.angle(g.spectral(x));
  if (angle > 0) x *= uniform() * kMultistartAngle / angle;
  return g.times_exp(y0, x);
}

// The multistart of the file comment after so_far (the plain or continued result); solve(equation, options) is
// the method's plain solve.
template <LieGroup G, class Solve>
SolveResult multistart(const Equation<G>& eq, const SolverOptions& opt, SolveResult so_far, Solve solve) {
  SolverOptions brief = opt;
  brief.max_iterations = std::min(opt.max_iterations, kMultistartIterations);
  int spent = 0, tried = 0;
  for (int k = 0; k < opt.multistart && !cancellation_requested(); ++k, ++tried) {
    Equation<G> e = eq;
    e.start_at(multistart_start(eq.group(), eq.start(), k));
    SolveResult r = solve(e, brief);
    if (!is_root(r)) {
      spent += r.iterations;
      continue;
    }
    r.found_by = Search::multistart;
    r.branch = so_far.status == Status::fold ? Branch::other : Branch::unchecked;
    r.multistart_start = k;
    r.multistart_tries = k + 1;
    r.fold_h = so_far.fold_h;
    r.path_h = so_far.path_h;
    r.continuation = std::move(so_far.continuation);
    r.extra_iterations = so_far.total_iterations() + spent;
    r.reason += "; found from seeded start " + std::to_string(k) + " (multistart), after: " + so_far.reason;
    return r;
  }
  so_far.multistart_tries = tried;
  so_far.extra_iterations += spent;
  so_far.reason += "; multistart: no root from " + std::to_string(tried) + " seeded starts";
  return so_far;
}

}  // namespace lienewton
