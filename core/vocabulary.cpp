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
    case ProblemKind::heavy_top:
      return {"heavy-top", "heavy-top (top under gravity, SO(3)×R³)", "heavy-top",
              "the heavy top on SO(3)×R³: R′ = R·ω̂, Jω′ = (Jω)×ω + m χ×(Rᵀγ)",
              "The heavy top, the benchmark of Lie group integrators for multibody systems (not in the paper): "
              "the state (R, ω) on SO(3)×R³ (group SOxR, 7×7 block-diagonal matrices), R′ = R·ω̂ and Jω′ = "
              "(Jω)×ω + m χ×(Rᵀγ), with mass m, centre of mass χ in the body, gravity γ in space and J the "
              "inertia about the pivot, J = J_c + m(|χ|²I − χχᵀ) from the principal moments J_c about the "
              "centre of mass (heavy_top.inertia, as the benchmark publishes them). Defaults m = 15, J_c = "
              "diag(0.234375, 0.46875, 0.234375), so J = diag(15.234375, 0.46875, 15.234375), χ = (0, 1, 0), "
              "γ = (0, 0, −9.81), R(0) = I, ω(0) = (0, 150, −4.61538): a fast spin about the body y-axis. The "
              "exact flow keeps the energy ½ωᵀJω − m γᵀRχ, the vertical angular momentum e₃ᵀRJω and, for this "
              "Lagrange top, the body spin ω_y."};
    case ProblemKind::stiff_body:
      return {"stiff-body", "stiff-body (sprung, damped and forced body, SO(3)×R³)", "stiff-body",
              "a stiff rigid body on SO(3)×R³: R′ = R·ω̂, Jω′ = (Jω)×ω − k·vee(skew R) − cω + f(t)",
              "A rigid body pulled toward the identity attitude by a torsional spring and damper, with a smooth "
              "forcing torque (not in the paper): the state (R, ω) on SO(3)×R³ (group SOxR, 7×7 block-diagonal "
              "matrices), R′ = R·ω̂ and Jω′ = (Jω)×ω − k·vee(skew R) − cω + f(t), skew R = (R − Rᵀ)/2, f(t) = "
              "(f₁ sin 2t, f₂ cos t, f₃). Defaults k = c = 10⁴, J = diag(1, 2, 3), f = (0.5, 0.3, 0.2), R(0) = "
              "exp(hat(0.5, −0.3, 0.8)), ω(0) = (1, −2, 0.5): the damper's eigenvalues are about −c/Jᵢ (−10⁴, "
              "−5·10³, −3.3·10³) against the slow part's ~1, the stiff benchmark of the implicit integrators. "
              "Forced and damped, it conserves nothing: it reports no invariants."};
    case ProblemKind::chain:
      return {"chain", "chain (k links, stiff damped joints, (SE(3)×R⁶)^k)", "chain",
              "k rigid links on (SE(3)×R⁶)^k hanging from a fixed point, joined by stiff springs and dampers",
              "A chain of k = n equal rigid links (not in the paper): link i's pose (Rᵢ, xᵢ) and body twist (ωᵢ, vᵢ) "
              "on SE(3)×R⁶ (group SExR^k, 11k×11k block-diagonal matrices), Rᵢ′ = Rᵢ·ω̂ᵢ, xᵢ′ = Rᵢvᵢ, m vᵢ′ = "
              "m vᵢ×ωᵢ + Rᵢᵀ(Fᵢ + mγ), Jωᵢ′ = (Jωᵢ)×ωᵢ + Σ a×(RᵢᵀF_a). The first link's top point hangs from "
              "the origin, each link's bottom point (0, 0, −L/2) is joined to the next one's top point (0, 0, "
              "L/2) by a penalty spherical joint: the force −k_s d − c d′ on the gap d between the two points. "
              "Defaults m = 1, L = 0.5, J = a rod of radius 0.05 (diag(0.02146, 0.02146, 0.00125)), γ = (0, 0, "
              "−9.81), k_s = 10⁵, c = 200, starting straight and at rest, turned by tilt = 0.6 rad about x from "
              "hanging down: a joint's period ≈ 0.02 s against the swing's ≈ 1.2 s and more, the stiff and damped "
              "regime of the implicit integrators. Its energy Σ ½m|vᵢ|² + ½ωᵢᵀJωᵢ − mγᵀxᵢ + Σ ½k_s|d_j|² "
              "decays as −c Σ|d_j′|²: reported as an invariant at c = 0 only."};
  }
  return {};
}

Words words(Invariant i) {
  switch (i) {
    case Invariant::energy:
      return {"energy", "Energy", "energy", "the energy, kinetic (and potential, heavy top and chain)",
              "The total energy of the state: ½ MᵀI⁻¹M, M = yᵀm, for the rigid body; ½ωᵀJω − m γᵀRχ for the "
              "heavy top (J about the pivot); Σ ½m|vᵢ|² + ½ωᵢᵀJωᵢ − mγᵀxᵢ + Σ ½k_s|d_j|² for the undamped chain. "
              "Evaluated from each returned state y, not from the integrator's stages. Its drift is relative to "
              "the rigid body's energy, to the heavy top's kinetic plus potential size ½ω₀ᵀJω₀ + m|γ||χ|, or to "
              "the chain's kinetic, springs' and m|γ||xᵢ| sizes summed (energy_scale)."};
    case Invariant::vertical_momentum:
      return {"vertical_momentum", "Vertical angular momentum", "vertical momentum",
              "the angular momentum about the vertical, e₃ᵀRJω (heavy top)",
              "The heavy top's angular momentum about the spatial vertical e₃, e₃ᵀRJω: gravity's torque leaves it "
              "unchanged when γ is vertical (as by default). Evaluated from each returned state y. Its drift is "
              "relative to the whole angular momentum |Jω₀| (vertical_momentum_scale), of which it is one "
              "component."};
    case Invariant::axial_spin:
      return {"axial_spin", "Spin about the symmetry axis", "axial spin",
              "the Lagrange top's body spin ω_k about its symmetry axis (heavy top)",
              "The heavy top's body angular velocity about its symmetry axis k, reported for a Lagrange top "
              "(χ along body axis k alone and the two other moments equal, as by default: k = y, ω_y = 150 "
              "for all t): neither (Jω)×ω nor gravity's torque m χ×(Rᵀγ) has a k component. Evaluated from "
              "each returned state y; its drift is relative to |ω₀| (axial_spin_scale)."};
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
      // Counted in terms of the series (3.9), not "order": an order here reads like a convergence order.
      return {"dexpinv-0", "dexp⁻¹ truncated after 1 term", "1 term", "dexp⁻¹ truncated after 1 term (3.10)",
              "dexp⁻¹ truncated after its first term (3.10): dexp⁻¹ᵥ(u) ≈ u, as if the group were commutative; for "
              "Version 2 the same truncation of dexp (3.16). Exact dg. Cheap, but only linear convergence "
              "once v = log(z⁻¹y) is not small."};
    case Differential::dexpinv_1:
      return {"dexpinv-1", "dexp⁻¹ truncated after 2 terms", "2 terms", "dexp⁻¹ truncated after 2 terms (3.11)",
              "dexp⁻¹ truncated after its first two terms (3.11): dexp⁻¹ᵥ(u) ≈ u + ½[v, u]; for Version 2 dexpᵥ(w) ≈ w "
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
    case Integrator::rkmk_gauss1:
      return {"rkmk-gauss1", "RKMK Gauss 1 (implicit midpoint)", "Gauss1",
              "implicit Runge–Kutta–Munthe-Kaas, 1-stage Gauss–Legendre (order 2)",
              "The implicit midpoint rule as a Runge–Kutta–Munthe-Kaas method (Munthe-Kaas 1999): one stage K = "
              "g(y·exp(hK/2)) in the algebra, y⁽ᵏ⁺¹⁾ = y⁽ᵏ⁾·exp(hK); dexp⁻¹ truncated to the identity, as order 2 "
              "allows. The stage system is solved by Newton in the algebra (either Newton method), or by the fixed "
              "point; second order, A-stable."};
    case Integrator::rkmk_gauss2:
      return {"rkmk-gauss2", "RKMK Gauss 2", "Gauss2",
              "implicit Runge–Kutta–Munthe-Kaas, 2-stage Gauss–Legendre (order 4)",
              "Two-stage Gauss–Legendre as a Runge–Kutta–Munthe-Kaas method: the coupled stages Kᵢ = dexp⁻¹_Θᵢ(g(y·"
              "exp Θᵢ)), Θᵢ = h Σ aᵢⱼKⱼ, with dexp⁻¹ (3.9) truncated after ad², solved as one system in the algebra "
              "by Newton (exact Jacobian, or frozen per step with dexpinv-0/1, or finite differences); fourth "
              "order, A-stable."};
    case Integrator::rkmk_gauss3:
      return {"rkmk-gauss3", "RKMK Gauss 3", "Gauss3",
              "implicit Runge–Kutta–Munthe-Kaas, 3-stage Gauss–Legendre (order 6)",
              "Three-stage Gauss–Legendre as a Runge–Kutta–Munthe-Kaas method: three coupled stages in the "
              "algebra, dexp⁻¹ (3.9) truncated after ad⁴, solved together by Newton; sixth order, A-stable."};
    case Integrator::rkmk_radau2:
      return {"rkmk-radau2", "RKMK Radau IIA 2", "Radau2",
              "implicit Runge–Kutta–Munthe-Kaas, 2-stage Radau IIA (order 3)",
              "Two-stage Radau IIA as a Runge–Kutta–Munthe-Kaas method: coupled stages in the algebra, dexp⁻¹ "
              "(3.9) truncated after ad¹, solved together by Newton; third order, L-stable and stiffly accurate: "
              "for stiff fields."};
    case Integrator::rkmk_radau3:
      return {"rkmk-radau3", "RKMK Radau IIA 3", "Radau3",
              "implicit Runge–Kutta–Munthe-Kaas, 3-stage Radau IIA (order 5)",
              "Three-stage Radau IIA as a Runge–Kutta–Munthe-Kaas method: coupled stages in the algebra, dexp⁻¹ "
              "(3.9) truncated after ad³, solved together by Newton; fifth order, L-stable and stiffly accurate."};
    case Integrator::rkmk4:
      return {"rkmk4", "RKMK4 (explicit)", "RKMK4", "explicit classical Runge–Kutta–Munthe-Kaas of order 4",
              "The classical fourth-order Runge–Kutta method in Munthe-Kaas form, with the exact dexp⁻¹: explicit, "
              "no equation to solve (method and differential are not used), so cheap per step but stable only "
              "while h‖dg‖ is small. The baseline that shows when implicit methods pay."};
    case Integrator::dirk_cg3:
      return {"dirk-cg3", "DIRK Crouch–Grossman 3", "DIRK-CG3", "L-stable 3-stage SDIRK in Crouch–Grossman form (order 3)",
              "A three-stage L-stable SDIRK method in Crouch–Grossman form (section 6), its "
              "coefficients solving the order-3 conditions of Crouch–Grossman methods (Owren & Marthinsen 1999), "
              "which add Σbᵢ²cᵢ + 2Σᵢ<ⱼ bᵢcᵢbⱼ = 1/3 to the classical ones; each stage y = z·exp(γh g(y)), "
              "γ ≈ 0.436, solved in sequence by the chosen method as dirk-cg2's; third order."};
    case Integrator::rkmk_lobatto3c:
      return {"rkmk-lobatto3c", "RKMK Lobatto IIIC 3", "Lobatto3C",
              "implicit Runge–Kutta–Munthe-Kaas, 3-stage Lobatto IIIC (order 4)",
              "Three-stage Lobatto IIIC as a Runge–Kutta–Munthe-Kaas method: coupled stages at c = 0, 1/2, 1 in "
              "the algebra, dexp⁻¹ (3.9) truncated after ad², solved together by Newton; fourth order, L-stable "
              "and stiffly accurate: damps stiff components as Radau IIA does, at Gauss 2's order."};
  }
  return {};
}

Words words(LinearSolver s) {
  switch (s) {
    case LinearSolver::auto_select: {
      static const std::string sentence =
          "LU up to N = " + std::to_string(kKrylovThreshold) + ", GMRES above (never by body count: a system of "
          "bodies is factored by sparse LU)";
      return {"auto", "Automatic", "auto", sentence, {}};
    }
    case LinearSolver::lu: return {"lu", "Dense LU", "LU", "dense LU of the Newton system", {}};
    case LinearSolver::gmres:
      return {"gmres", "GMRES", "GMRES", "matrix-free GMRES with the Eisenstat–Walker forcing term", {}};
  }
  return {};
}

Words words(Factorization f) {
  switch (f) {
    case Factorization::dense_lu:
      return {"dense-lu", "Dense LU", "dense LU", "dense LU with partial pivoting of the assembled Newton matrix", {}};
    case Factorization::sparse_lu: {
      static const std::string sentence =
          "sparse LU (COLAMD ordering, partial pivoting) of the assembled Newton matrix: systems of bodies with "
          "more than " + std::to_string(kDenseLuMaxDim) + " unknowns";
      return {"sparse-lu", "Sparse LU", "sparse LU", sentence, {}};
    }
    case Factorization::gmres:
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

Words words(Branch b) {
  switch (b) {
    case Branch::continued:
      return {"continued", "z's branch", "continued",
              "the root continued from y = z at h = 0: z's branch of roots followed to h, no fold passed",
              "The implicit Euler step y = z·exp(h g(y)) (1.1) has many roots; the one an integrator needs is the "
              "root that continues y = z from h = 0 (section 5). continued: continuation followed that branch "
              "of roots from (z, 0) to the requested h without passing a fold, and the returned y is its root."};
    case Branch::other:
      return {"other", "another root", "other",
              "known not to be the root continued from z: the branch folds before h, or this root lies elsewhere",
              {}};
    case Branch::unchecked:
      return {"unchecked", "unchecked", "unchecked",
              "which root this is was not checked (a plain solve; ask for continuation to know)", {}};
  }
  return {};
}

Words words(Search s) {
  switch (s) {
    case Search::plain: return {"plain", "Plain solve", "plain", "the method's solve from the request's start", {}};
    case Search::continuation:
      return {"continuation", "Continuation", "continuation",
              "pseudo-arclength continuation of z's branch of roots from h = 0", {}};
    case Search::multistart:
      return {"multistart", "Multistart", "multistart", "one of the seeded starts around the request's start", {}};
  }
  return {};
}

Words words(PathPointKind k) {
  switch (k) {
    case PathPointKind::path: return {"path", "Path point", "path", "a corrected point of z's branch", {}};
    case PathPointKind::final:
      return {"final", "Solve at h", "final", "the method's solve at the requested h from the path's prediction", {}};
    case PathPointKind::fold:
      return {"fold", "Fold", "fold", "the branch turns back in h here: no continued root beyond", {}};
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
    case Status::fold:
      return {"fold", "fold", "fold", "z's branch of roots turns back before h: no continued root there", {}};
    case Status::cancelled: return {"cancelled", "cancelled", "cancelled", "cancelled, not computed", {}};
    case Status::min_step:
      return {"min_step", "below minimum step", "min step",
              "adaptive steps: the error or a failing stage asked for a step below the minimum step", {}};
    case Status::max_steps:
      return {"max_steps", "max steps", "max steps", "adaptive steps: the bound on steps was reached before t_end",
              {}};
  }
  return {};
}

}  // namespace lienewton
