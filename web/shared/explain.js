// "What is this?" for the choices a paper reader meets in the forms: each problem's g, each method and each
// differential, with the equation numbers of Owren & Welfert (BIT 2000). A value not listed here (a new one
// the server added) falls back to the server catalog's one-line description.
import { entries, entry } from './catalog.js';
import { el } from './dom.js';

const EXPLAIN = {
  problem: {
    'paper-linear': 'Section 5, first example (Figure 5.1): one implicit Euler step y = z\u00b7exp(h g(y)) of '
      + 'y\u2032 = y\u00b7g(y) on SO(N), solved as f(y) = log(z\u207b\u00b9y) \u2212 h g(y) = 0 (3.6). '
      + 'g(y) = diag(diag(y,1),1) \u2212 diag(diag(y,1),\u22121): the skew-symmetric matrix whose first '
      + 'super-diagonal is that of y. g is linear in y, so dg\u1d67(u) = g(yu). z = y\u207d\u2070\u207e is a random '
      + 'rotation (QR of a random matrix, from the seed).',
    'paper-sine': 'Section 5, second example (Figure 5.2): the same implicit Euler step (3.6) with the nonlinear '
      + 'g(y) = U \u2212 U\u1d40, U = sin(y)\u00b7(2y \u2212 5y\u00b2) (sin entry by entry, matrix products), from a '
      + 'random rotation z.',
    'rigid-body': 'The free rigid body on SO(3) (not in the paper\u2019s section 5): y\u2032 = y\u00b7g(y) with '
      + 'g(y) = hat(I\u207b\u00b9 y\u1d40m), the body angular velocity from the constant spatial angular momentum m '
      + 'and the principal moments of inertia I. The exact flow keeps the energy E = \u00bd M\u1d40I\u207b\u00b9M, '
      + 'M = y\u1d40m. N = 3 only.',
  },
  method: {
    'fixed-point': 'Fixed-point iteration (1.2): y\u2099\u208a\u2081 = z\u00b7exp(h g(y\u2099)). No differential, '
      + 'no linear system; converges linearly, and only while h\u2016dg\u2016 is small.',
    'newton-group': 'Newton Version 1, on the group (3.5): solve df\u1d67\u2099(u\u2099) + f(y\u2099) = 0 for '
      + 'u\u2099 in the algebra, then y\u2099\u208a\u2081 = y\u2099\u00b7exp(u\u2099). For the implicit Euler step '
      + 'the linear system is (3.8): dexp\u207b\u00b9(u\u2099) \u2212 h dg(u\u2099) + f(y\u2099) = 0.',
    'newton-algebra': 'Newton Version 2, in the algebra (3.20): write y\u2099 = z\u00b7exp(v\u2099), solve '
      + 'df\u0303\u1d65\u2099(u\u2099) + f\u0303(v\u2099) = 0 with f\u0303(v) = v \u2212 h g(z\u00b7exp(v)) (3.21), '
      + 'then v\u2099\u208a\u2081 = v\u2099 + u\u2099: classical Newton on the algebra, through (3.22).',
  },
  integrator: {
    'implicit-euler': 'Implicit Lie group Euler (1.1): y\u207d\u1d4f\u207a\u00b9\u207e = y\u207d\u1d4f\u207e\u00b7exp(h g(y\u207d\u1d4f\u207a\u00b9\u207e)), '
      + 'one equation (3.6) per step, solved by the chosen method; first order.',
    'dirk-cg2': 'A two-stage L-stable, stiffly accurate SDIRK method in Crouch\u2013Grossman form (section 6): '
      + 'each stage is an equation y = z\u00b7exp(\u03b3h g(y)), \u03b3 = 1 \u2212 1/\u221a2, of the same kind, '
      + 'solved in sequence by the chosen method; second order.',
  },
  differential: {
    'finite-difference': 'Finite differences (3.18): df\u1d67(u) \u2248 (f(y\u00b7exp(tu)) \u2212 f(y)) / t with '
      + 't = O(\u221au) (u the unit round-off), one residual evaluation per basis direction: q = N(N\u22121)/2 '
      + 'per Newton step. What the paper\u2019s experiments used.',
    'dexpinv-0': 'dexp\u207b\u00b9 truncated after order 0 (3.10): dexp\u207b\u00b9\u1d65(u) \u2248 u, as if the group '
      + 'were commutative; for Version 2 the same truncation of dexp (3.16). Exact dg. Cheap, but only '
      + 'linear convergence once v = log(z\u207b\u00b9y) is not small.',
    'dexpinv-1': 'dexp\u207b\u00b9 truncated after order 1 (3.11): dexp\u207b\u00b9\u1d65(u) \u2248 u + \u00bd[v, u]; '
      + 'for Version 2 dexp\u1d65(w) \u2248 w \u2212 \u00bd[v, w] (3.17). Exact dg.',
    exact: 'The exact differential: the whole series (3.9) for dexp\u207b\u00b9 (closed forms on SO(3)) and the '
      + 'exact dg of the problem, so Newton converges quadratically near the root.',
  },
};

export function explanation(name, value) {
  return EXPLAIN[name]?.[value] ?? entry(name, value).description;
}

export const EXPLAINED = Object.keys(EXPLAIN);

// A disclosure under a select that explains its current value, kept in step with the select.
export function explainer(select) {
  const text = el('p', { class: 'about-text' });
  const box = el('details', { class: 'about', dataset: { about: select.name } },
    el('summary', {}, 'What is this?'), text);
  const sync = () => { text.textContent = explanation(select.name, select.value); };
  select.addEventListener('change', sync);
  select.addEventListener('input', sync);
  sync();
  return box;
}

// One disclosure for a tick table or checkbox list: every value of the named enums with its explanation.
export function explainerList(names) {
  return el('details', { class: 'about', dataset: { about: names.join(' ') } },
    el('summary', {}, 'What do these mean?'),
    el('dl', { class: 'about-text' }, names.flatMap((name) => entries(name).flatMap((e) => [
      el('dt', {}, e.label), el('dd', { dataset: { value: e.value } }, explanation(name, e.value))]))));
}
