#pragma once
// Where each Newton version lives and how it moves, so that the globalised iteration (globalization.hpp) is
// written once for both:
//   GroupChart    Version 1 (3.5): iterates y_n on the group, f = f(y) of (3.6), D = df_y, y -> y exp(s);
//   AlgebraChart  Version 2 (3.20): iterates v_n in the algebra, f = f~(v) of (3.21), D = df~_v, v -> v + s.
#include <limits>

#include "equation.hpp"

namespace lienewton {

// Per unit of N: an iterate whose defect (||y^T y - I||_F on SO(N)) exceeds this times N is replaced by the
// group's projection of it (the polar factor on SO(N)).
inline constexpr double kProjectionDefect = 16.0 * std::numeric_limits<double>::epsilon();

template <LieGroup G>
class GroupChart {
 public:
  using Point = typename Equation<G>::Point;
  using State = typename G::Element;
  using Vector = typename G::Vector;
  using Operator = typename G::Operator;
  // phi = 1/2 ||f||^2 jumps where z^-1 y turns through angle pi: f of (3.6) holds log (solvers/watchdog.hpp).
  static constexpr bool kMeritJumps = true;

  GroupChart(const Equation<G>& eq, Differential d)
      : eq_(eq), d_(d), z_inv_(eq.group().inverse(eq.z())),
        // Difference quotients need f alone, also at y_n: the same log path as in the perturbed points.
        need_(d == Differential::finite_difference ? Equation<G>::Need::residual : Equation<G>::Need::differential) {}

  const Equation<G>& equation() const { return eq_; }
  Differential differential() const { return d_; }
  Point at(const State& y) const { return eq_.at(y, need_); }
  // (3.5): y exp(s). Long products drift off the group by rounding (a random walk of ~eps per step); the
  // group's projection puts the iterate back before the drift reaches the floor's scale.
  State move(const Point& p, const Vector& s, bool& projected) const {
    const G& group = eq_.group();
    State next = group.times_exp(p.y, s);
    projected = next.allFinite() && group.defect(next) > kProjectionDefect * group.n();
    if (projected) next = group.project(next);
    return next;
  }
  Operator matrix(const Point& p) const { return eq_.df_matrix(p, d_); }
  FactoredOperator<Operator> factored_matrix(const Point& p) const { return eq_.df_factored(p, d_); }
  Vector apply(const Point& p, const Vector& w) const { return eq_.df(p, w, d_); }
  // ||z^-1 y||_F, watched for divergence: constant on a compact group (sqrt(N) on SO(N)), growing with the
  // translation on SE(3) and R^k, where an iterate can run away.
  double size(const Point& p) const { return eq_.group().compose(z_inv_, p.y).norm(); }
  static constexpr const char* kSizeName = "||z^-1 y||_F";

 private:
  const Equation<G>& eq_;
  Differential d_;
  State z_inv_;
  typename Equation<G>::Need need_;
};

template <LieGroup G>
class AlgebraChart {
 public:
  using Point = typename Equation<G>::Point;
  using State = typename G::Vector;
  using Vector = typename G::Vector;
  using Operator = typename G::Operator;
  // f~ of (3.21) has no log: phi is as smooth as g.
  static constexpr bool kMeritJumps = false;

  AlgebraChart(const Equation<G>& eq, Differential d) : eq_(eq), d_(d) {}

  const Equation<G>& equation() const { return eq_; }
  Differential differential() const { return d_; }
  // f~(v) (3.21), and ||f(y)|| at y = z exp(v) as section 5 measures every method (needs log of z^-1 y).
  Point at(const State& v) const {
    Point p = eq_.at_algebra(v);
    eq_.read_group_residual(p);
    return p;
  }
  State move(const Point& p, const Vector& s, bool& projected) const {  // (3.20): v + s
    projected = false;
    return p.v + s;
  }
  Operator matrix(const Point& p) const { return eq_.dftilde_matrix(p, d_); }
  FactoredOperator<Operator> factored_matrix(const Point& p) const { return eq_.dftilde_factored(p, d_); }
  Vector apply(const Point& p, const Vector& w) const { return eq_.dftilde(p, w, d_); }
  double size(const Point& p) const { return p.v.norm(); }  // ||v||, watched for divergence
  static constexpr const char* kSizeName = "||v||";

 private:
  const Equation<G>& eq_;
  Differential d_;
};

}  // namespace lienewton
