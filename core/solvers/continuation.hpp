#pragma once
// Continuation (request field "continuation"): the root of the implicit Euler equation (1.1) that continues y = z
// from h = 0, found by following z's branch of roots and nothing else. Section 5: "fairly good initial values are
// available due to the continuity of the solution". In the algebra's coordinates, y = z exp(v), the roots are the
// zeros of
//   F(v, tau) = v - tau g(z exp v)                                                               (3.21)
// with F(0, 0) = 0, D_v F = I - tau dg_y dexp_v (3.22) and D_tau F = -g(y). Pseudo-arclength continuation of the
// curve x(s) = (v(s), tau(s)) (Keller 1977; Allgower & Georg, "Numerical Continuation Methods", 1990, ch. 2):
//   tangent     t with [D_v F  D_tau F] t = 0, ||t|| = 1, oriented along the previous one (at (0, 0): (g(z), 1));
//   predictor   x + ds t, its move in v at most kMaxPredictorMove;
//   corrector   Newton on the bordered system F(x) = 0, t^T (x - x_pred) = 0, accepted only when its corrections
//               contract by kMaxContraction (affine covariant Newton: Deuflhard, "Newton Methods for Nonlinear
//               Problems", 2004, sec. 5.1) and stay within kAcceptRadius of the predictor's move in v, the
//               tangent turns by less than kMaxTurn, and the link from the last point is certified (below), unless
//               the branch turned back along it (a fold) or it moves v by at most kUncertifiedMove (near a fold no
//               link certifies); otherwise ds is halved;
//   fold        the tangent's tau-component changes sign: the branch turns back at fold_h (interpolated), and no
//               root continued from z exists beyond it;
//   at h        when the predictor passes h, the method's own solve at exactly h starts from the predictor there
//               (the explicit Lie-Euler value when the path starts at (0, 0)); when the corrector carries tau past
//               h instead, from the secant between the last two path points at tau = h; its root is the continued one when
//               the same contraction and radius tests hold of its iterates and the segment from the last path point
//               to it is certified (branch_certificate.hpp: one root in a ball around the segment for every tau
//               between, carried continuously; the radius test alone once took a root of another branch that lay
//               nearer the tangent's prediction on a curved branch). Otherwise the path's corrector at fixed
//               tau = h computes the root, certified the same way, and the method starts there; failing that the
//               path goes on with a shorter step, down to links short enough to certify.
// The path's own Newton uses the exact D_v F (the search must know the branch's geometry, whatever differential
// the method uses); the caller times the whole search. Only the method's solve at h decides the result's status, y, residual and trace.
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/cancellation.hpp"
#include "core/solver_options.hpp"
#include "branch_certificate.hpp"
#include "spectrum.hpp"
#include "equation.hpp"
#include "iteration_monitor.hpp"
#include "newton_step.hpp"
#include "solve_result.hpp"

namespace lienewton {

inline constexpr int kMaxPathPoints = 400;          // predictor-corrector steps, accepted or not
inline constexpr int kMaxCorrectorIterations = 8;
inline constexpr double kMaxContraction = 0.5;      // Newton: each correction at most half the previous one
inline constexpr double kFixedPointContraction = 0.95;  // the fixed point contracts linearly (Banach)
inline constexpr double kAcceptRadius = 0.25;       // a root at most a quarter of the predictor's move in v from it
inline constexpr double kAcceptFloor = 1e-3;        // (plus this, for steps along which v hardly moves) ...
inline constexpr double kMaxCorrection = 0.5;       // ... and never farther than this (other roots lie O(1) away)
inline constexpr double kMaxPredictorMove = 0.5;    // a predictor step, to h included, moves v by at most this
inline constexpr double kFirstStep = 1.0 / 16;      // a path step at most doubles tau, and is at most this from 0
inline constexpr double kMaxTurn = 0.5;             // radians between successive tangents
inline constexpr int kFoldBisections = 30;          // to locate a fold ...
inline constexpr double kFoldBracket = 1e-5;        // ... within this arclength (relative): fold_h to ~1e-10
inline constexpr int kCertificateMaxDim = 32;       // the largest algebra whose links are certified ...
inline constexpr double kUncertifiedMove = kAcceptFloor;  // ... and path steps moving v by more than this
// A stiff step (h ||dg||_F > 1) that damps a component by h |Re mu| >= kDissipative: no fixed matrix contracts over
// [0, h] there, and the linearisation's argument decides (docs/continuation.md).
inline constexpr double kDissipative = 10.0;

// How far from a prediction that moved by `move` (in the algebra) its corrected root may lie.
inline double acceptance_radius(double move) { return std::min(kMaxCorrection, kAcceptRadius * move + kAcceptFloor); }

// The records of a solve at step h, tagged with h, for the caller's callback.
inline TraceCallback tagged_with_step(const TraceCallback& cb, double h) {
  if (!cb) return {};
  return [&cb, h](const TraceRecord& r) {
    TraceRecord t = r;
    t.stage_h = h;
    return cb(t);
  };
}

// Whether a solve's iterates converged as they do near a regular root: a root (converged or at its rounding
// floor) reached by steps that contract as Newton's do (the fixed point's: as a contraction). Steps below
// kNegligibleStep are not compared: they cannot move y to another root, and at large h rounding makes them wander.
inline constexpr double kNegligibleStep = 1e-8;
inline bool contracted_to_root(const SolveResult& r, Method method) {
  if (!is_root(r)) return false;
  const double theta = method == Method::fixed_point ? kFixedPointContraction : kMaxContraction;
  const double rounding = kNegligibleStep;
  double previous = std::numeric_limits<double>::infinity();
  for (std::size_t n = 1; n <= static_cast<std::size_t>(r.iterate) && n < r.trace.size(); ++n) {
    const double step = r.trace[n].step;
    if (step > rounding && step > theta * previous) return false;
    previous = step;
  }
  return true;
}

// Where the method's first solve at h starts: at the tangent's prediction (the solve route); at z itself (an
// integrator's predictor none); or at the tangent's and, where that fails on a stiff stage, at the linearly implicit
// value (an integrator's stages: see BranchPath::linearly_implicit).
enum class FirstTry { tangent, z, tangent_then_linear };

template <LieGroup G>
class BranchPath {
 public:
  using Element = typename G::Element;
  using Vector = typename G::Vector;
  // The method's solve of an equation (started where it says), with its callback.
  using Solve = std::function<SolveResult(const Equation<G>&, const TraceCallback&)>;

  // eq: the implicit Euler equation at the requested h; method: the request's (for the contraction test).
  BranchPath(const Equation<G>& eq, Method method, const TraceCallback& cb, Solve solve,
             FirstTry first_try = FirstTry::tangent)
      : eq_(eq), group_(eq.group()), method_(method), cb_(cb), solve_(std::move(solve)), h_(eq.h()),
        q_(eq.group().dim()), first_from_z_(first_try == FirstTry::z),
        then_linear_(first_try == FirstTry::tangent_then_linear),
        dense_(!detail::use_krylov(eq.group(), LinearSolver::auto_select)) {}

  SolveResult run() {
    Point x{zero_vector(group_), 0.0};
    Tangent t = tangent_at_start();
    if (!dense_) return finish(without_path(t));
    double ds = std::numeric_limits<double>::infinity();  // the first try goes straight to h
    bool first = true;
    for (int k = 0; k < kMaxPathPoints; ++k) {
      if (cancellation_requested()) return stopped(x, "cancelled");
      ds = std::min(ds, kMaxPredictorMove / std::max(t.v.norm(), 1e-300));
      if (t.th > 0.0 && x.h + ds * t.th >= h_) {
        const double to_h = (h_ - x.h) / t.th;
        if (auto r = at_h(x, Point{x.v + to_h * t.v, h_}, to_h * t.v.norm(), PathStep{t.th, to_h}, first))
          return finish(std::move(*r));
        if (first && then_linear_) {
          if (auto r = linearly_implicit()) return finish(std::move(*r));
        }
        first = false;
        ds = to_h / 2;
        if (cancellation_requested()) return stopped(x, "cancelled");
      }
      ds = std::min(ds, std::max(x.h, kFirstStep) / std::max(t.th, 1e-300));  // tau at most doubles
      if (ds < kSmallestStep * (1.0 + x.h + x.v.norm())) return stopped(x, "its step length fell below its smallest");
      const Point pred{x.v + ds * t.v, x.h + ds * t.th};
      const auto next = correct(pred, t, ds * t.v.norm());
      if (!next) {
        ds /= 2;
        continue;
      }
      const Tangent tn = tangent_at(*next, t);
      if (!tn.valid || tn.v.dot(t.v) + tn.th * t.th < std::cos(kMaxTurn)) {
        ds /= 2;
        continue;
      }
      if (tn.th <= 0.0 && t.th > 0.0) {  // the branch turned back in h between x and next
        const auto [before, fold_h] = turning_point(x, t, Bracket{0.0, t.th, ds, tn.th, next->point});
        if (fold_h < h_) return fold(before, fold_h);
        ds = (h_ - x.h) / t.th;  // the branch reaches h before it turns: go straight there
        continue;
      }
      if (next->point.h >= h_) {
        // The corrector carried tau past h although the predictor stayed below it: h lies between x and next,
        // so the secant between them at tau = h predicts the root there. Accepting next instead would leave
        // the path beyond h, where no step leads back.
        const double w = (h_ - x.h) / (next->point.h - x.h);
        const Point pred{x.v + w * (next->point.v - x.v), h_};
        if (auto r = at_h(x, pred, (pred.v - x.v).norm(), PathStep{tn.th, w * ds}, first))
          return finish(std::move(*r));
        first = false;
        ds /= 2;
        continue;
      }
      // Another branch may have taken the corrector: a shorter link. Near a fold D_v F is almost singular and no
      // link certifies; below kUncertifiedMove the radius test's floor alone keeps the branch.
      if (ds * t.v.norm() > kUncertifiedMove && !certified(x, next->point)) {
        ds /= 2;
        continue;
      }
      record(PathPointKind::path, next->point, tn.th, ds, next->iterations, next->residual, Status::converged);
      if (!cb_ok_) return stopped(next->point, "cancelled");
      x = next->point;
      t = tn;
      ds *= next->iterations <= 2 ? 2.0 : next->iterations <= 4 ? 1.0 : 0.5;
    }
    return stopped(x, "it took " + std::to_string(kMaxPathPoints) + " steps");
  }

 private:
  static constexpr double kSmallestStep = 1e-10;

  struct Point {
    Vector v;
    double h = 0;
  };
  struct Tangent {
    Vector v;
    double th = 0;
    bool valid = true;
  };
  struct Corrected {
    Point point;
    int iterations = 0;
    double residual = 0;
  };

  // F(v, tau) and its Jacobian [D_v F  D_tau F], bordered by the row c^T: the corrector's and the tangent's matrix.
  struct Linearized {
    Eigen::VectorXd f;      // F(v, tau)
    DynamicOperator<G> a;   // D_v F (sparse for a system of bodies)
    Eigen::VectorXd d_tau;  // D_tau F = -g
    double scale = 0;       // 1 + ||v|| + tau ||g||: what F's rounding is relative to
  };
  // [D_v F  D_tau F; row^T  corner] x = rhs. A sparse D_v F stays sparse (its border adds 2q + 1 entries) and is
  // factored by NewtonLu; a singular one gives NaN, as the dense LU's infinities do.
  Eigen::VectorXd bordered_solve(const Linearized& l, const Vector& row, double corner,
                                 const Eigen::VectorXd& rhs) const {
    if constexpr (kSparseOperator<G>) {
      std::vector<Eigen::Triplet<double>> entries;
      entries.reserve(static_cast<std::size_t>(l.a.nonZeros() + 2 * q_ + 1));
      for (Eigen::Index c = 0; c < l.a.outerSize(); ++c)
        for (typename DynamicOperator<G>::InnerIterator it(l.a, c); it; ++it)
          entries.emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()), it.value());
      for (int i = 0; i < q_; ++i) {
        entries.emplace_back(i, q_, l.d_tau[i]);
        entries.emplace_back(q_, i, row[i]);
      }
      entries.emplace_back(q_, q_, corner);
      Eigen::SparseMatrix<double> m(q_ + 1, q_ + 1);
      m.setFromTriplets(entries.begin(), entries.end());
      detail::NewtonLu<double> lu;
      if (!lu.factorize(m)) return Eigen::VectorXd::Constant(q_ + 1, std::numeric_limits<double>::quiet_NaN());
      return lu.solve(rhs);
    } else {
      Eigen::MatrixXd m(q_ + 1, q_ + 1);
      m.topLeftCorner(q_, q_) = l.a;
      m.topRightCorner(q_, 1) = l.d_tau;
      m.bottomLeftCorner(1, q_) = Eigen::VectorXd(row).transpose();
      m(q_, q_) = corner;
      return Eigen::PartialPivLU<Eigen::MatrixXd>(m).solve(rhs);
    }
  }
  Linearized linearize(const Point& x) const {
    const Equation<G> e = eq_.at_step(x.h);
    const auto p = e.at_algebra(x.v);
    const Vector g = e.field()->g(p.y);
    Linearized l;
    l.f = Eigen::VectorXd(p.f);
    l.a = DynamicOperator<G>(e.dftilde_matrix(p, Differential::exact));
    l.d_tau = -Eigen::VectorXd(g);
    l.scale = 1.0 + x.v.norm() + x.h * g.norm();
    return l;
  }

  // A stiff stage (h ||dg_z||_F > 1), where the tangent's prediction is no guide, predicted by its linearly implicit
  // value v = (I - h dg_z)^-1 h g(z), the zero of F linearised at (0, 0) (3.22): when I - tau dg_z stays regular for
  // every tau in [0, h] (no eigenvalue mu of dg_z with h |mu| >= 1 and Re mu > 0), the linearisation's root is
  // continuous from v = 0, so a root within the acceptance radius of v, reached by contracting steps, is taken as the
  // continued one, as for an implicit RKMK stage (rkmk_stages.hpp). That is an argument about the linearisation, not
  // a certificate: a fixed A cannot contract over [0, h] when h |mu| >> 1 (docs/continuation.md). Its linear solve
  // counts as an iteration.
  std::optional<SolveResult> linearly_implicit() {
    const Spectrum& j = spectrum_at_z();
    if (!(h_ * j.norm() > 1.0) || !j.stays_regular(h_)) return std::nullopt;
    const Eigen::MatrixXd a = Eigen::MatrixXd::Identity(q_, q_) - h_ * j.matrix();
    const Eigen::VectorXd hg = h_ * Eigen::VectorXd(eq_.field()->g(eq_.z()));
    const Eigen::VectorXd x = Eigen::PartialPivLU<Eigen::MatrixXd>(a).solve(hg);
    ++extra_iterations_;
    if (!x.allFinite()) return std::nullopt;
    Point pred{zero_vector(group_), h_};
    pred.v = x;
    return at_h(Point{zero_vector(group_), 0.0}, pred, x.norm(), PathStep{}, false, Link::linearised);
  }

  Tangent tangent_at_start() const {
    Tangent t{Vector(eq_.field()->g(eq_.z())), 1.0};
    const double norm = std::sqrt(t.v.squaredNorm() + 1.0);
    t.v /= norm;
    t.th /= norm;
    return t;
  }

  // The unit tangent at x oriented along previous: [D_v F  D_tau F; previous^T] t = (0, 1).
  Tangent tangent_at(const Corrected& c, const Tangent& previous) const {
    const Linearized l = linearize(c.point);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(q_ + 1);
    rhs[q_] = 1.0;
    const Eigen::VectorXd t = bordered_solve(l, previous.v, previous.th, rhs);
    Tangent out;
    const double norm = t.norm();
    out.valid = t.allFinite() && norm > 0.0;
    if (!out.valid) return out;
    out.v = Vector(t.head(q_) / norm);
    out.th = t[q_] / norm;
    return out;
  }

  // Newton on F(x) = 0, c^T (x - pred) = 0 from pred (c = the tangent: pseudo-arclength; c = (0, 1): tau fixed),
  // accepted as in the file comment; move: the predictor's move in v.
  std::optional<Corrected> correct(const Point& pred, const Tangent& c, double move) const {
    const double radius = acceptance_radius(move);
    Point x = pred;
    double previous = std::numeric_limits<double>::infinity();
    for (int it = 0; it <= kMaxCorrectorIterations; ++it) {
      throw_if_cancelled();
      if (x.h < 0.0) return std::nullopt;
      const Linearized l = linearize(x);
      if (!l.f.allFinite()) return std::nullopt;
      const double residual = l.f.norm();
      if (residual <= kPathTolerance * l.scale) return Corrected{x, it, residual};
      if (it == kMaxCorrectorIterations) return std::nullopt;
      Eigen::VectorXd rhs(q_ + 1);
      rhs.head(q_) = -l.f;
      rhs[q_] = -(c.v.dot(x.v - pred.v) + c.th * (x.h - pred.h));
      const Eigen::VectorXd dx = bordered_solve(l, c.v, c.th, rhs);
      const double step = dx.norm();
      if (!dx.allFinite() || (it > 0 && step > kMaxContraction * previous &&
                              step > 1e3 * std::numeric_limits<double>::epsilon() * l.scale))
        return std::nullopt;
      previous = step;
      x.v += Vector(dx.head(q_));
      x.h += dx[q_];
      if ((x.v - pred.v).norm() > radius) return std::nullopt;
    }
    return std::nullopt;
  }

  // The fold between x (arclength 0 along t) and a point past it: the bracket [s_lo, s_hi] of the sign change of
  // the tangent's h-component, narrowed by bisection (each point corrected from x along t), then h at the zero of
  // tau'(s), taken linear across the bracket. Near a fold h(s) = h* - c (s - s*)^2, so a bracket of width w puts
  // h* within c w^2. Returns the bracket's lower point (the branch's last point before the fold) and h*.
  struct Bracket {
    double s_lo, th_lo, s_hi, th_hi;
    Point hi;
  };
  std::pair<Point, double> turning_point(const Point& x, const Tangent& t, Bracket b) const {
    Point lo = x;
    for (int k = 0; k < kFoldBisections && b.s_hi - b.s_lo > kFoldBracket * (1.0 + b.s_hi); ++k) {
      const double mid = 0.5 * (b.s_lo + b.s_hi);
      const auto c = correct(Point{x.v + mid * t.v, x.h + mid * t.th}, t, mid * t.v.norm());
      if (!c) break;
      const Tangent tc = tangent_at(*c, t);
      if (!tc.valid) break;
      if (tc.th > 0.0) {
        b.s_lo = mid, b.th_lo = tc.th, lo = c->point;
      } else {
        b.s_hi = mid, b.th_hi = tc.th, b.hi = c->point;
      }
    }
    const double zero = (b.s_hi - b.s_lo) * b.th_lo / (b.th_lo - b.th_hi);
    return {lo, std::max({lo.h + b.th_lo * zero / 2, lo.h, b.hi.h})};
  }

  struct PathStep {  // what the path's record of the root at h says of the step that reached it
    double dh_ds = 0;
    double ds = 0;
  };
  // The method's solve at h from the prediction pred, made at the path's point `from` and moving v by `move` (or
  // from z, the first time, with first_from_z), then from the path's own root at h; a result when one of them
  // reached the continued root, or when the method fails from that root itself (the method's answer at h, which the
  // caller labels).
  // How the link from `from` to the root at h is shown to follow the branch: certified (branch_certificate.hpp), or
  // by the linearised argument of linearly_implicit() for a stiff stage.
  enum class Link { certified, linearised };
  std::optional<SolveResult> at_h(const Point& from, const Point& pred, double move, PathStep step, bool first,
                                  Link link = Link::certified) {
    const double radius = acceptance_radius(move);
    const std::optional<Point> certify_from = link == Link::certified ? std::optional<Point>(from) : std::nullopt;
    const Element y_pred = group_.times_exp(eq_.z(), pred.v);
    const bool from_z = first && first_from_z_;
    if (group_.angle(group_.spectral(pred.v)) < G::kLogRadius) {
      SolveResult r = solve_from(from_z ? eq_.z() : y_pred);
      if (is_continued(r, certify_from, pred, radius)) return labelled(std::move(r), Branch::continued);
      spent(r);
    }
    const Tangent fixed_h{zero_vector(group_), 1.0};
    const auto root = correct(pred, fixed_h, move);
    if (!root || (certify_from && !certified(*certify_from, root->point))) return std::nullopt;
    record(PathPointKind::path, root->point, step.dh_ds, step.ds, root->iterations, root->residual,
           Status::converged);
    const Element y_root = group_.times_exp(eq_.z(), root->point.v);
    if (group_.angle(group_.spectral(root->point.v)) >= G::kLogRadius) return beyond_log(root->point);
    SolveResult r = solve_from(y_root);
    const double near = 1e-6 * (1.0 + root->point.v.norm());
    if (is_continued(r, std::nullopt, root->point, near)) return labelled(std::move(r), Branch::continued);
    // The method does not keep the continued root from the root itself: its answer, and that it is not z's.
    const Branch branch = is_root(r) ? Branch::other : Branch::unchecked;
    r.reason = "the method, started at the root continued from z (||F|| = " + format_number(root->residual) +
               "), ended: " + r.reason;
    return labelled(std::move(r), branch);
  }

  // Where Newton goes matrix-free (large N), the path's dense bordered systems would cost O(q^3) each, longer than
  // any deadline allows between two polls: only the method's solve at h from the tangent's prediction, accepted by
  // the same test when that prediction moves v by at most kMaxPredictorMove; otherwise the method's solve from the
  // given start, unchecked.
  SolveResult without_path(const Tangent& t) {
    const double to_h = h_ / t.th;
    const double move = to_h * t.v.norm();
    const Point pred{to_h * t.v, h_};
    if (move <= kMaxPredictorMove && group_.angle(group_.spectral(pred.v)) < G::kLogRadius) {
      SolveResult r = solve_from(first_from_z_ ? eq_.z() : group_.times_exp(eq_.z(), pred.v));
      if (is_continued(r, std::nullopt, pred, acceptance_radius(move))) return labelled(std::move(r), Branch::continued);
      spent(r);
    }
    SolveResult r = solve_from(eq_.start());
    r.path_h = 0.0;
    r.reason = "continuation without the path (its dense systems are beyond the matrix-free size N > " +
               std::to_string(kKrylovThreshold) + "), so which root this is was not checked; " + r.reason;
    return labelled(std::move(r), Branch::unchecked);
  }

  SolveResult solve_from(const Element& start) {
    Equation<G> e = eq_;
    e.start_at(start);
    SolveResult r = solve_(e, tagged_with_step(cb_, h_));
    record(PathPointKind::final, Point{}, 0.0, 0.0, r.iterations, r.residual, r.status);
    return r;
  }

  // Whether r's y is the root nearest the prediction pred (within radius): the tests of the file comment, its
  // coordinates v = log(z^-1 y) within radius of pred's and, given the path's point `from` the prediction was made
  // at, the segment from there to v certified.
  bool is_continued(const SolveResult& r, const std::optional<Point>& from, const Point& pred, double radius) const {
    if (!contracted_to_root(r, method_)) return false;
    try {
      double angle = 0;
      const Vector v = group_.log_vector(group_.compose(group_.inverse(eq_.z()), Element(r.y)), angle);
      return (v - pred.v).norm() <= radius && (!from || certified(*from, Point{v, h_}));
    } catch (const LogDomainError&) {
      return false;
    }
  }

  // Whether the root `to` is the one continued from the path's point `from` (branch_certificate.hpp), with
  // D_v F(v, tau) = I - tau M(v), M(v) = dg_{z exp v} dexp_v, and F(v, tau) = v - tau g(z exp v) (3.21), (3.22).
  // Above kCertificateMaxDim its dense O(q^3) algebra would outweigh the step it checks, and on a dissipative stiff
  // stage it cannot hold: the path's tests decide there.
  bool certified(const Point& from, const Point& to) const {
    if (q_ > kCertificateMaxDim || dissipative()) return true;
    const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(q_, q_);
    const Equation<G> unit = eq_.at_step(1.0);  // D_v F = I - M at tau = 1
    const auto m_at = [&](const typename Equation<G>::Point& p) {
      return Eigen::MatrixXd(identity - Eigen::MatrixXd(DynamicOperator<G>(unit.dftilde_matrix(p, Differential::exact))));
    };
    const Vector c = (from.v + to.v) / 2;
    const auto at_c = unit.at_algebra(c);
    const Eigen::MatrixXd m_c = m_at(at_c);
    const Eigen::VectorXd g_c(eq_.field()->g(at_c.y));
    BranchLink link{.x_a = Eigen::VectorXd(from.v), .x_b = Eigen::VectorXd(to.v), .tau_a = from.h, .tau_b = to.h,
                    .d_a = from.h == 0.0 ? identity : Eigen::MatrixXd(identity - from.h * m_at(unit.at_algebra(from.v))),
                    .d_b = identity - to.h * m_at(unit.at_algebra(to.v)), .d_mid = {}, .f_mid = {}};
    const auto taus = BranchLink::taus(from.h, to.h);
    for (std::size_t k = 0; k < taus.size(); ++k) {
      link.d_mid[k] = identity - taus[k] * m_c;
      link.f_mid[k] = Eigen::VectorXd(c) - taus[k] * g_c;
    }
    return certify_link(link).holds;
  }

  // h max(-Re mu) >= kDissipative for an eigenvalue mu of dg_z (then h ||dg_z||_F > 1 too: the stage is stiff).
  bool dissipative() const { return spectrum_at_z().decays_faster_than(kDissipative / h_); }
  // dg_z and its eigenvalues, formed once for the stage.
  const Spectrum& spectrum_at_z() const {
    if (!spectrum_at_z_) spectrum_at_z_.emplace(Eigen::MatrixXd(DynamicOperator<G>(eq_.field()->dg_matrix(group_, eq_.z()))));
    return *spectrum_at_z_;
  }

  void spent(const SolveResult& r) { extra_iterations_ += r.iterations; }

  void record(PathPointKind kind, const Point& x, double dh_ds, double ds, int iterations, double residual,
              Status status) {
    PathPoint p;
    p.kind = kind;
    p.h = kind == PathPointKind::final ? h_ : x.h;
    if (kind != PathPointKind::final) {
      p.distance = x.v.norm();
      p.angle = group_.angle(group_.spectral(x.v));
      p.dh_ds = dh_ds;
      p.step_length = ds;
      extra_iterations_ += iterations;
    }
    p.iterations = iterations;
    p.residual = residual;
    p.status = status;
    points_.push_back(p);
    if (cb_ && kind != PathPointKind::final) {
      TraceRecord rec;
      rec.iteration = static_cast<int>(points_.size()) - 1;
      rec.residual = residual;
      rec.angle = p.angle;
      rec.log_boundary_distance = log_boundary_distance<G>(group_.principal_angle(p.angle));
      rec.stage_h = p.h;
      rec.path_point = p;
      cb_ok_ = cb_(rec) && cb_ok_;
    }
  }

  // A result whose y is the point x of the path (a fold, a stop), described at the requested h.
  SolveResult at_point(const Point& x, Status status) const {
    SolveResult r;
    r.status = status;
    r.y = group_.times_exp(eq_.z(), x.v);  // an Element, as the solvers' y (requests_on_group.hpp converts)
    const auto p = eq_.at(Element(r.y), Equation<G>::Need::residual);
    r.residual = p.in_domain ? p.residual : std::numeric_limits<double>::quiet_NaN();
    r.orthogonality_error = group_.defect(Element(r.y));
    r.z_adjustment = eq_.z_adjustment();
    return r;
  }

  SolveResult fold(const Point& x, double fold_h) {
    record(PathPointKind::fold, x, 0.0, 0.0, 0, 0.0, Status::fold);
    SolveResult r = at_point(x, Status::fold);
    r.fold_h = fold_h;
    r.reason = "z's branch of roots turns back at h = " + format_number(fold_h) + " < " + format_number(h_) +
               ": no root continued from z exists at h; returned the branch's point at h = " + format_number(x.h) +
               ", whose ||f(y)|| at h is " + format_number(r.residual);
    return finish(labelled(std::move(r), Branch::other));
  }

  // The continued root at h has left log's principal branch: y solves (1.1), f of (3.6) cannot see it.
  SolveResult beyond_log(const Point& x) const {
    SolveResult r = at_point(x, Status::off_branch);
    r.reason = "the root continued from z has h g(y) beyond " + std::string(G::kAngleName) + " " +
               G::kLogBoundaryName + ": y solves y = z exp(h g(y)), but log(z^-1 y) != h g(y) and ||f(y)|| = " +
               format_number(r.residual);
    return labelled(std::move(r), Branch::continued);
  }

  // The path stopped short of h: the method's solve at h from the given start, unchecked.
  SolveResult stopped(const Point& x, const std::string& why) {
    SolveResult r = cancellation_requested() || !cb_ok_ ? at_point(x, Status::cancelled) : solve_from(eq_.start());
    if (r.status == Status::cancelled && r.reason.empty()) r.reason = "cancelled during continuation";
    r.path_h = x.h;
    r.reason = "continuation stopped at h = " + format_number(x.h) + " (" + why + "); " + r.reason;
    return finish(labelled(std::move(r), Branch::unchecked));
  }

  static SolveResult labelled(SolveResult r, Branch branch) {
    r.branch = branch;
    r.found_by = Search::continuation;
    return r;
  }

  SolveResult finish(SolveResult r) {
    for (TraceRecord& rec : r.trace) rec.stage_h = h_;
    r.continuation = std::move(points_);
    r.extra_iterations += extra_iterations_;
    if (r.continuation.size() > 1)
      r.reason += "; continuation: " + std::to_string(r.continuation.size()) + " path points, " +
                  std::to_string(r.total_iterations()) + " iterations in all";
    return r;
  }

  static constexpr double kPathTolerance = 1e-10;  // relative to 1 + ||v|| + tau ||g||

  const Equation<G>& eq_;
  const G& group_;
  Method method_;
  const TraceCallback& cb_;
  Solve solve_;
  const double h_;
  const int q_;
  const bool first_from_z_;
  const bool then_linear_;
  const bool dense_;  // the path's bordered systems are solved densely: only below the matrix-free size
  bool cb_ok_ = true;
  mutable std::optional<Spectrum> spectrum_at_z_;  // see spectrum_at_z()
  std::vector<PathPoint> points_;
  int extra_iterations_ = 0;
};

}  // namespace lienewton
