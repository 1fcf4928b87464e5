#include "core/vocabulary.hpp"

#include <string>

#include "core/solvers/newton_step.hpp"

namespace lienewton {

Words words(ProblemKind p) {
  switch (p) {
    case ProblemKind::paper_linear:
      return {"paper-linear", "paper-linear (§5, linear g)", "paper-linear",
              "section 5: g(y) = diag(diag(y,1),1) − diag(diag(y,1),−1), linear in y",
              "Section 5, first example (Figure 5.1): one implicit Euler step y = z·exp(h g(y)) of y′ = "
              "y·g(y) on SO(N), solved as f(y) = log(z⁻¹y) − h g(y) = 0 (3.6). g(y) = diag(diag(y,1),1) − "
              "diag(diag(y,1),−1): the skew-symmetric matrix whose first super-diagonal is that of y. g is "
              "linear in y, so dgᵧ(u) = g(yu). z = y⁽⁰⁾ is a random rotation (QR of a random matrix, from "
              "the seed)."};
    case ProblemKind::paper_sine:
      return {"paper-sine", "paper-sine (§5, sine g)", "paper-sine",
              "section 5: g(y) = U − Uᵀ with U = sin.(y)(2y − 5y²)",
              "Section 5, second example (Figure 5.2): the same implicit Euler step (3.6) with the "
              "nonlinear g(y) = U − Uᵀ, U = sin(y)·(2y − 5y²) (sin entry by entry, matrix products), from a "
              "random rotation z."};
    case ProblemKind::rigid_body:
      return {"rigid-body", "rigid-body (free rigid body)", "rigid-body",
              "the free rigid body on SO(3) (inertia and momentum given)",
              "The free rigid body on SO(3) (not in the paper’s section 5): y′ = y·g(y) with g(y) = hat(I⁻¹ "
              "yᵀm), the body angular velocity from the constant spatial angular momentum m and the "
              "principal moments of inertia I. The exact flow keeps the energy E = ½ MᵀI⁻¹M, M = yᵀm. N = 3 "
              "only."};
  }
  return {};
}

Words words(Method m) {
  switch (m) {
    case Method::fixed_point:
      return {"fixed-point", "Fixed point (1.2)", "Fixed point", "fixed-point iteration (1.2)",
              "Fixed-point iteration (1.2): yₙ₊₁ = z·exp(h g(yₙ)). No differential, no linear system; "
              "converges linearly, and only while h‖dg‖ is small."};
    case Method::newton_group:
      return {"newton-group", "Newton V1, group (3.5)", "Newton group", "Newton's method on the group, Version 1 (3.5)",
              "Newton Version 1, on the group (3.5): solve dfᵧₙ(uₙ) + f(yₙ) = 0 for uₙ in the algebra, then "
              "yₙ₊₁ = yₙ·exp(uₙ). For the implicit Euler step the linear system is (3.8): dexp⁻¹(uₙ) − h "
              "dg(uₙ) + f(yₙ) = 0."};
    case Method::newton_algebra:
      return {"newton-algebra", "Newton V2, algebra (3.20)", "Newton algebra",
              "Newton's method in the algebra, Version 2 (3.20)",
              "Newton Version 2, in the algebra (3.20): write yₙ = z·exp(vₙ), solve df̃ᵥₙ(uₙ) + f̃(vₙ) = 0 "
              "with f̃(v) = v − h g(z·exp(v)) (3.21), then vₙ₊₁ = vₙ + uₙ: classical Newton on the algebra, "
              "through (3.22)."};
  }
  return {};
}

Words words(Differential d) {
  switch (d) {
    case Differential::finite_difference:
      return {"finite-difference", "Finite differences", "FD", "finite-difference differential (3.18)",
              "Finite differences (3.18): dfᵧ(u) ≈ (f(y·exp(tu)) − f(y)) / t with t = O(√u) (u the unit "
              "round-off), one residual evaluation per basis direction: q = N(N−1)/2 per Newton step. What "
              "the paper’s experiments used."};
    case Differential::dexpinv_0:
      return {"dexpinv-0", "dexp⁻¹ to order 0", "order 0", "dexp⁻¹ truncated after order 0 (3.10)/(3.11)",
              "dexp⁻¹ truncated after order 0 (3.10): dexp⁻¹ᵥ(u) ≈ u, as if the group were commutative; for "
              "Version 2 the same truncation of dexp (3.16). Exact dg. Cheap, but only linear convergence "
              "once v = log(z⁻¹y) is not small."};
    case Differential::dexpinv_1:
      return {"dexpinv-1", "dexp⁻¹ to order 1", "order 1", "dexp⁻¹ truncated after order 1 (3.10)/(3.11)",
              "dexp⁻¹ truncated after order 1 (3.11): dexp⁻¹ᵥ(u) ≈ u + ½[v, u]; for Version 2 dexpᵥ(w) ≈ w "
              "− ½[v, w] (3.17). Exact dg."};
    case Differential::exact:
      return {"exact", "Exact dexp⁻¹", "exact", "the exact dexp⁻¹",
              "The exact differential: the whole series (3.9) for dexp⁻¹ (closed forms on SO(3)) and the "
              "exact dg of the problem, so Newton converges quadratically near the root."};
  }
  return {};
}

Words words(Integrator i) {
  switch (i) {
    case Integrator::implicit_euler:
      return {"implicit-euler", "Implicit Euler", "Euler", "implicit Lie group Euler (1.1)",
              "Implicit Lie group Euler (1.1): y⁽ᵏ⁺¹⁾ = y⁽ᵏ⁾·exp(h g(y⁽ᵏ⁺¹⁾)), one equation (3.6) per step, "
              "solved by the chosen method; first order."};
    case Integrator::dirk_cg2:
      return {"dirk-cg2", "DIRK Crouch–Grossman 2", "DIRK-CG2", "L-stable SDIRK in Crouch–Grossman form (section 6)",
              "A two-stage L-stable, stiffly accurate SDIRK method in Crouch–Grossman form (section 6): "
              "each stage is an equation y = z·exp(γh g(y)), γ = 1 − 1/√2, of the same kind, solved in "
              "sequence by the chosen method; second order."};
  }
  return {};
}

Words words(LinearSolver s) {
  switch (s) {
    case LinearSolver::auto_select: {
      static const std::string sentence = "LU up to N = " + std::to_string(kKrylovThreshold) + ", GMRES above";
      return {"auto", "Automatic", "auto", sentence, {}};
    }
    case LinearSolver::lu: return {"lu", "Dense LU", "LU", "dense LU of the Newton system", {}};
    case LinearSolver::gmres:
      return {"gmres", "GMRES", "GMRES", "matrix-free GMRES with the Eisenstat–Walker forcing term", {}};
  }
  return {};
}

Words words(Stopping s) {
  switch (s) {
    case Stopping::residual:
      return {"residual", "Residual ‖f(y)‖ (the paper's test)", "residual",
              "stop when ‖f(yₙ)‖ = ‖log(z⁻¹yₙ) − h g(yₙ)‖ ≤ tol, as the paper measures every method in section 5",
              {}};
    case Stopping::algebra_residual:
      return {"algebra-residual", "Algebra residual ‖f̃(v)‖ (3.21)", "algebra residual",
              "Version 2 and the fixed point stop when ‖f̃(vₙ)‖ ≤ tol (3.21), blind to log's branch", {}};
  }
  return {};
}

Words words(Globalization g) {
  switch (g) {
    case Globalization::none:
      return {"none", "None (the paper's full steps)", "plain", "Newton's full step every iteration, as the paper",
              {}};
    case Globalization::line_search:
      return {"line-search", "Line search (Armijo, LM fallback)", "line search",
              "Armijo backtracking on 1/2 ||f||^2, Levenberg-Marquardt when Newton's step is no descent", {}};
    case Globalization::trust_region:
      return {"trust-region", "Trust region (dogleg)", "trust region",
              "dogleg steps on 1/2 ||f + D s||^2 inside a radius", {}};
  }
  return {};
}

Words words(Predictor p) {
  switch (p) {
    case Predictor::none:
      return {"none", "None (start at Zᵢ)", "none", "each stage's iteration starts at Zᵢ, as the paper's at y₀ = z",
              {}};
    case Predictor::lie_euler:
      return {"lie-euler", "Lie–Euler", "Lie-Euler",
              "each stage starts at the explicit Lie–Euler value Zᵢ·exp(h aᵢᵢ g(Zᵢ)) (residual O(h²), not O(h)) "
              "when its residual is the smaller",
              {}};
  }
  return {};
}

Words words(StageStart s) {
  switch (s) {
    case StageStart::given: return {"start", "Request's start", "start", "the request's start (z or y0)", {}};
    case StageStart::root: return {"root", "Previous root", "root", "the previous stage's root", {}};
    case StageStart::identity:
      return {"identity", "Identity", "identity", "the identity of z's component", {}};
    case StageStart::restart:
      return {"restart", "Seeded restart", "restart", "one of the seeded starts around the request's start", {}};
  }
  return {};
}

// A status has one name for a reader: the PNG legends print its short label (ASCII), the dashboard its label.
Words words(Status s) {
  switch (s) {
    case Status::converged: return {"converged", "converged", "converged", "converged: ‖f(y)‖ ≤ tol", {}};
    case Status::max_iterations:
      return {"max_iterations", "max iterations", "max iterations", "max iterations reached above tol", {}};
    case Status::diverged: return {"diverged", "diverged", "diverged", "diverged: residual or step blew up", {}};
    case Status::non_finite:
      return {"non_finite", "non-finite", "non-finite", "non-finite: NaN or Inf appeared", {}};
    case Status::left_log_domain:
      return {"left_log_domain", "left log domain", "left log domain", "left the log domain (angle reached π)", {}};
    case Status::singular_differential:
      return {"singular_differential", "singular differential", "singular differential", "singular Newton system",
              {}};
    case Status::stagnated: return {"stagnated", "stagnated", "stagnated", "stagnated at the rounding floor", {}};
    case Status::off_branch:
      return {"off_branch", "off branch", "off branch", "solved, but h g(y) beyond angle π (off branch)", {}};
    case Status::local_minimum:
      return {"local_minimum", "local minimum", "local minimum",
              "stationary point of ½‖f‖² that is no root (globalised)", {}};
    case Status::no_descent:
      return {"no_descent", "no descent", "no descent", "no step decreases ½‖f‖² (globalised; φ not smooth there)",
              {}};
    case Status::cancelled: return {"cancelled", "cancelled", "cancelled", "cancelled, not computed", {}};
  }
  return {};
}

}  // namespace lienewton
