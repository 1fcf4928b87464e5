#pragma once
// The coupled stage system of an implicit Runge-Kutta-Munthe-Kaas step (Munthe-Kaas, "High order Runge-Kutta
// methods on manifolds", Appl. Numer. Math. 29 (1999)) for y' = y g(t, y) from y_k at t_k, step h, and an
// s-stage tableau (a, b, c) (tableau.hpp, methods.cpp):
//   F_i(K) = K_i - dexpinv~_{Theta_i}(w_i) = 0,   w_i = g(t_k + c_i h, Y_i),  Y_i = y_k exp(Theta_i),
//   Theta_i = h sum_j a_ij K_j,                   y_k+1 = y_k exp(h sum_j b_j K_j),
// dexpinv~ the series (3.9) truncated after ad^q (q: the tableau's dexpinv_degree(), p - 2). The unknowns are the s stages
// K_i in the algebra's coordinates, stacked: the section 6 remark's "general RK methods", solved as one system in
// the algebra (the form of Version 2, (3.20)). Its Jacobian is dF_i/dK_j = delta_ij I - h a_ij M_i with
//   M_i = d/dTheta (dexpinv~_Theta(w_i)) + dexpinv~_{Theta_i} dg_{Y_i} dexp_{Theta_i}           (cf. (3.22)).
// The request's differential picks the Newton matrix:
//   exact              that Jacobian at every iterate: Newton on the truncated system, quadratic;
//   dexpinv-1          frozen per step at the first iterate, with dexpinv ~ I + ad/2 (3.11), dexp ~ I - ad/2 (3.17);
//   dexpinv-0          I - h A (x) dg_{y_k}, dexpinv ~ dexp ~ I (3.10)/(3.16): the classical simplified Newton,
//                      solved block by block (stage_decoupling.hpp) and kept across iterations and steps by the
//                      caller while it contracts;
//   finite-difference  forward differences of F at every iterate (3.19);
// and the fixed point (method fixed-point) iterates K <- dexpinv~_{Theta_i}(w_i). Newton Version 1 and 2 are the
// same iteration here: the system already lives in the algebra.
//
// Which root: at h = 0 the system's root is K_i = g(t_k, y_k) for every i, and the step needs the root continued
// from it. continued_stages() accepts the method's solve when its iterates contract (kMaxContraction; the fixed
// point's kFixedPointContraction) and its Theta lies within acceptance_radius of a prediction on the branch:
//   h ||dg_{y_k}|| <= 1   from the caller's start, around the branch's tangent Theta_i = c_i h g(t_k, y_k) (the
//                         tests continuation.hpp applies to a stage of (1.1));
//   h ||dg_{y_k}|| > 1    (stiff) from the caller's start under the test above when the caller asks (the last
//                         step's root passed that test: the tangent still guides this motion) and the start is a
//                         prediction; otherwise, or where that fails, from K = 0, around its first Newton iterate:
//                         the linearly implicit stages
//                         K = (I - h A (x) J)^-1 (g(t_k + c_i h, y_k))_i, exact for a field linear in the chart, and
//                         on the linearisation's branch from h = 0 where I - tau A (x) J stays regular for every tau
//                         in [0, h] (linearisation_regular(): J's large eigenvalues dissipative); where it may not,
//                         as the tangent's regime;
// and, unless the step is dissipative (h |Re mu| >= kDissipative: the linearisation's argument decides), the
// segment from h = 0 to the root certified (certified_link: no other branch between). Otherwise it follows the
// branch from h = 0 by natural-parameter continuation in h (tangent, then secant predictor; exact Newton corrector
// with the same two tests and each link that moves by more than kUncertifiedMove certified; step controlled as
// continuation.hpp's), and the method's solve at h must stay at the branch's root. docs/integrators.md.
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/cancellation.hpp"
#include "core/groups/bernoulli.hpp"
#include "core/problems.hpp"
#include "core/solver_options.hpp"
#include "core/solvers/branch_certificate.hpp"
#include "core/solvers/continuation.hpp"
#include "core/solvers/eigenvalues.hpp"
#include "core/solvers/spectrum.hpp"
#include "core/solvers/iteration_monitor.hpp"
#include "stage_decoupling.hpp"
#include "tableau.hpp"

namespace lienewton {

struct StageSolution {
  Eigen::VectorXd k;                // the stacked stages K_1 .. K_s
  Status status = Status::max_iterations;
  int iterations = 0;               // of every solve it took (continuation's correctors included)
  std::vector<double> residuals;    // h ||F(K_n)||, n = 0, 1, ..., of the last solve
  bool continued = false;           // the root continued from h = 0
  bool near_tangent = false;        // that root lies within the tangent's test of its prediction (see continued_stages)
  std::string reason;
  Eigen::VectorXd first_iterate;    // K after the last solve's first step (its start if it took none)
  double contraction = 0;           // the largest ratio of successive corrections of the last solve
  int jacobian_evaluations = 0;     // Newton matrices formed (the caller's decoupled one not counted here)
  int factorizations = 0;
  std::optional<Factorization> factorization;  // how the Newton matrices were factored, if any was
  double residual() const { return residuals.empty() ? 0.0 : residuals.back(); }
};

template <LieGroup G>
class RkmkStages {
 public:
  using Element = typename G::Element;
  using Vector = typename G::Vector;
  // The stage system's matrices: sparse for a group with sparse operators (its bodies' couplings kept).
  using Matrix = DynamicOperator<G>;

  struct Evaluation {
    Eigen::VectorXd f;  // F(K), stacked
    std::vector<Vector> theta, w;
    std::vector<Element> y;
  };

  RkmkStages(const G& group, VectorField<G>& field, const integrators::Tableau& tab, Element y, double t, double h)
      : group_(group), field_(&field), tab_(&tab), y_(std::move(y)), t_(t), h_(h), q_(group.dim()) {}

  // The same system at another step size (continuation in h).
  RkmkStages at_step(double h) const {
    RkmkStages s = *this;
    s.h_ = h;
    return s;
  }

  int size() const { return tab_->stages() * q_; }
  double h() const { return h_; }
  // h ||dg_{y_k}||_F: above 1 the step is stiff (the tangent's prediction is no guide to the root).
  double stiffness() const { return h_ * jacobian_at_start().norm(); }
  // Whether I - tau A (x) J, J = dg_{y_k}, is regular for every tau in [0, h], so that the linearly implicit stages
  // lie on the linearisation's branch from h = 0: every eigenvalue mu of hJ is small (|mu| rho(A) < 1: a Neumann
  // series) or has Re mu <= 0 (then mu lambda is never real and positive for an eigenvalue lambda of A, whose real
  // part is positive in every implicit tableau here).
  // A system too large for a dense LU (a sparse one above dense_lu_max_dim()) would pay O(q^3) for the
  // eigenvalues at every step: regularity is then not known, and the stages follow the branch from h = 0.
  bool linearisation_regular() const {
    if (kSparseOperator<G> && q_ > dense_lu_max_dim()) return false;
    return spectrum_at_start().stays_regular(h_ * eigenvalues_of(tab_->a).cwiseAbs().maxCoeff());
  }
  // Whether the step damps a component of J = dg_{y_k} strongly: h (-Re mu) >= kDissipative for an eigenvalue mu
  // (never where the eigenvalues would cost O(q^3) at every step, as for linearisation_regular()).
  bool dissipative() const {
    if (kSparseOperator<G> && q_ > dense_lu_max_dim()) return false;
    return spectrum_at_start().decays_faster_than(kDissipative / h_);
  }
  Vector stage(const Eigen::VectorXd& k, int i) const { return Vector(k.segment(i * q_, q_)); }
  Vector theta(const Eigen::VectorXd& k, int i) const {
    Vector th = zero_vector(group_);
    for (int j = 0; j < tab_->stages(); ++j) th += (h_ * tab_->a(i, j)) * stage(k, j);
    return th;
  }
  Eigen::VectorXd thetas(const Eigen::VectorXd& k) const {
    Eigen::VectorXd out(size());
    for (int i = 0; i < tab_->stages(); ++i) out.segment(i * q_, q_) = Eigen::VectorXd(theta(k, i));
    return out;
  }
  // g(t_k, y_k): every stage's value at h = 0.
  Vector g_at_start() const {
    field_->set_time(t_);
    return field_->g(y_);
  }
  // Every stage K_i = g, stacked: with g = g(t_k, y_k) the root at h = 0, and the tangent's prediction.
  Eigen::VectorXd constant(const Vector& g) const { return along(g, zero_vector(group_)); }
  // Stages K_i = g + c_i h slope, stacked.
  Eigen::VectorXd along(const Vector& g, const Vector& slope) const {
    Eigen::VectorXd k(size());
    for (int i = 0; i < tab_->stages(); ++i) k.segment(i * q_, q_) = Eigen::VectorXd(g + (tab_->c(i) * h_) * slope);
    return k;
  }
  // dK/dh at h = 0: differentiating F(K, h) = 0 there gives dK_i/dh = c_i dg_{y_k}(g(t_k, y_k)).
  Eigen::VectorXd slope_at_zero() const {
    field_->set_time(t_);
    const Vector dk = field_->dg(y_, field_->g(y_));
    Eigen::VectorXd slope(size());
    for (int i = 0; i < tab_->stages(); ++i) slope.segment(i * q_, q_) = Eigen::VectorXd(tab_->c(i) * dk);
    return slope;
  }
  // y_k+1 = y_k exp(h sum_j b_j K_j).
  Element next(const Eigen::VectorXd& k) const {
    Vector u = zero_vector(group_);
    for (int j = 0; j < tab_->stages(); ++j) u += (h_ * tab_->b(j)) * stage(k, j);
    return group_.times_exp(y_, u);
  }

  Evaluation evaluate(const Eigen::VectorXd& k) const {
    Evaluation e;
    e.f.resize(size());
    for (int i = 0; i < tab_->stages(); ++i) {
      e.theta.push_back(theta(k, i));
      e.y.push_back(group_.times_exp(y_, e.theta[i]));
      field_->set_time(t_ + tab_->c(i) * h_);
      e.w.push_back(field_->g(e.y[i]));
      e.f.segment(i * q_, q_) = Eigen::VectorXd(stage(k, i) - truncated_dexpinv(e.theta[i], e.w[i]));
    }
    return e;
  }

  // dexpinv~_theta(w) = sum_{k <= q} beta_k ad_theta^k(w): beta_0 = 1, beta_1 = 1/2, beta_2p = B_2p / (2p)! (3.9).
  Vector truncated_dexpinv(const Vector& theta, const Vector& w) const {
    Vector x = w, sum = w;
    for (int k = 1; k <= tab_->dexpinv_degree(); ++k) {
      x = group_.bracket(theta, x);
      if (const double beta = coefficient(k); beta != 0.0) sum += beta * x;
    }
    return sum;
  }

  // The Newton matrix of the differential d at k (see the file comment).
  Matrix jacobian(const Eigen::VectorXd& k, const Evaluation& e, Differential d) const {
    if (d == Differential::finite_difference) {
      Eigen::MatrixXd m(size(), size());
      const double step = std::sqrt(std::numeric_limits<double>::epsilon()) * std::max(1.0, k.norm());
      for (int j = 0; j < size(); ++j) {
        throw_if_cancelled();
        Eigen::VectorXd kj = k;
        kj[j] += step;
        m.col(j) = (evaluate(kj).f - e.f) / step;
      }
      if constexpr (kSparseOperator<G>) {
        return m.sparseView();
      } else {
        return m;
      }
    }
    std::vector<Matrix> stage_m;
    if (d == Differential::dexpinv_0) {
      field_->set_time(t_);
      stage_m.assign(static_cast<std::size_t>(tab_->stages()), Matrix(field_->dg_matrix(group_, y_)));
    } else {
      for (int i = 0; i < tab_->stages(); ++i) {
        field_->set_time(t_ + tab_->c(i) * h_);
        stage_m.push_back(d == Differential::dexpinv_1 ? first_order_m(e, i) : exact_m(e, i));
      }
    }
    if constexpr (kSparseOperator<G>) {
      // I - h A (x) M_i, block by block from the M_i's nonzeros (duplicates summed).
      std::vector<Eigen::Triplet<double>> entries;
      for (int r = 0; r < size(); ++r) entries.emplace_back(r, r, 1.0);
      for (int i = 0; i < tab_->stages(); ++i)
        for (int j = 0; j < tab_->stages(); ++j) {
          const double c = h_ * tab_->a(i, j);
          if (c == 0.0) continue;
          const Matrix& mi = stage_m[static_cast<std::size_t>(i)];
          for (Eigen::Index col = 0; col < mi.outerSize(); ++col)
            for (typename Matrix::InnerIterator it(mi, col); it; ++it)
              entries.emplace_back(static_cast<int>(i * q_ + it.row()), static_cast<int>(j * q_ + it.col()),
                                   -c * it.value());
        }
      Matrix m(size(), size());
      m.setFromTriplets(entries.begin(), entries.end());
      return m;
    } else {
      Eigen::MatrixXd m = Eigen::MatrixXd::Identity(size(), size());
      for (int i = 0; i < tab_->stages(); ++i)
        for (int j = 0; j < tab_->stages(); ++j)
          m.block(i * q_, j * q_, q_, q_) -= (h_ * tab_->a(i, j)) * stage_m[static_cast<std::size_t>(i)];
      return m;
    }
  }

  // The request's method from k: Newton (the Jacobian of d, frozen per solve for dexpinv-0/1; with `simplified`, its
  // factored decoupled matrix for dexpinv-0) or the fixed point. Stops when within_tolerance(), and as soon as a step
  // fails to contract. Every start is examined: a predictor is accepted only on its residual.
  StageSolution solve(Eigen::VectorXd k, Method method, Differential d, const SolverOptions& opt,
                      const integrators::DecoupledNewtonMatrix* simplified = nullptr) const {
    StageSolution out;
    const bool newton = method != Method::fixed_point;
    const bool frozen = d == Differential::dexpinv_0 || d == Differential::dexpinv_1;
    const bool decoupled = newton && simplified && d == Differential::dexpinv_0;
    const double contraction = newton ? kMaxContraction : kFixedPointContraction;
    const double kappa = stiffness();
    detail::NewtonLu<double> lu;
    double previous = std::numeric_limits<double>::infinity();
    for (int n = 0;; ++n) {
      throw_if_cancelled();
      const Evaluation e = evaluate(k);
      const double r = h_ * e.f.norm();
      const double before = out.residuals.empty() ? std::numeric_limits<double>::infinity() : out.residuals.back();
      out.residuals.push_back(r);
      if (!std::isfinite(r)) {
        out.status = Status::non_finite;
        out.reason = "the stage residual is not finite";
        break;
      }
      // The absolute test with the conservative floor: a residual within it that stops improving is solved
      // (within_tolerance), as is one whose next correction fails to contract, rounding's doing at that size.
      const bool within_absolute = r <= std::max(opt.tol, conservative_floor(e, kappa));
      if (within_tolerance(r, before, k, e, opt, kappa, n, within_absolute, n == opt.max_iterations)) {
        out.status = Status::converged;
        out.reason = "h ||F(K)|| = " + format_number(r) + " after " + std::to_string(n) + " iterations";
        break;
      }
      if (n == opt.max_iterations) {
        out.status = Status::max_iterations;
        out.reason = "h ||F(K)|| = " + format_number(r) + " after " + std::to_string(n) + " iterations";
        break;
      }
      Eigen::VectorXd dk = -e.f;  // the fixed point: K_i <- dexpinv~_{Theta_i}(w_i)
      if (decoupled) {
        dk = simplified->solve(-e.f);
      } else if (newton) {
        if (!frozen || n == 0) {
          ++out.jacobian_evaluations;
          ++out.factorizations;
          const bool regular = lu.factorize(jacobian(k, e, d));
          out.factorization = lu.factorization();
          if (!regular) {
            out.status = Status::singular_differential;
            out.reason = "the stage system's Newton matrix is singular";
            break;
          }
        }
        dk = lu.solve(-e.f);
      }
      const double step = h_ * dk.norm();
      if (!std::isfinite(step) || (step > kNegligibleStep && step > contraction * previous)) {
        if (within_absolute && std::isfinite(step)) {
          out.status = Status::converged;
          out.reason = "h ||F(K)|| = " + format_number(r) + " after " + std::to_string(n) +
                       " iterations, at rounding (the next correction did not contract)";
          break;
        }
        out.status = Status::diverged;
        out.reason = "iteration " + std::to_string(n + 1) + " did not contract (h ||dK|| = " + format_number(step) +
                     " after " + format_number(previous) + ")";
        break;
      }
      if (n > 0 && step > kNegligibleStep) out.contraction = std::max(out.contraction, step / previous);
      previous = step;
      k += dk;
      if (n == 0) out.first_iterate = k;
    }
    if (out.first_iterate.size() == 0) out.first_iterate = k;
    out.iterations = static_cast<int>(out.residuals.size()) - 1;
    out.k = std::move(k);
    return out;
  }

 private:
  static double coefficient(int k) {
    if (k == 1) return 0.5;
    return k % 2 == 0 ? bernoulli_over_factorial(k / 2) : 0.0;
  }

  // M_i of the exact Jacobian: d/dTheta of sum beta_k ad_Theta^k(w) is sum beta_k sum_m ad^m ad_delta ad^(k-1-m) w,
  // and ad_delta x = -ad_x delta.
  Matrix exact_m(const Evaluation& e, int i) const {
    const Vector& th = e.theta[static_cast<std::size_t>(i)];
    const Vector& w = e.w[static_cast<std::size_t>(i)];
    const Matrix ad = Matrix(group_.ad_matrix(th));
    const int q = tab_->dexpinv_degree();
    std::vector<Matrix> ad_pow{identity()};
    std::vector<Vector> ad_w{w};  // ad^j w
    for (int j = 1; j <= q; ++j) {
      ad_pow.push_back(ad * ad_pow.back());
      ad_w.push_back(group_.bracket(th, ad_w.back()));
    }
    Matrix op = identity(), d_theta = Matrix(identity() * 0.0);
    for (int k = 1; k <= q; ++k) {
      const double beta = coefficient(k);
      if (beta == 0.0) continue;
      op += beta * ad_pow[static_cast<std::size_t>(k)];
      for (int m = 0; m < k; ++m)
        d_theta -= beta * Matrix(ad_pow[static_cast<std::size_t>(m)] *
                                 Matrix(group_.ad_matrix(ad_w[static_cast<std::size_t>(k - 1 - m)])));
    }
    const Matrix dg = Matrix(field_->dg_matrix(group_, e.y[static_cast<std::size_t>(i)]));
    return d_theta + Matrix(Matrix(op * dg) * Matrix(group_.dexp_matrix(group_.spectral(th))));
  }

  // M_i with dexpinv ~ I + ad/2 (3.11) and dexp ~ I - ad/2 (3.17): -ad_w/2 + (I + ad/2) dg (I - ad/2).
  Matrix first_order_m(const Evaluation& e, int i) const {
    const Matrix half_ad = 0.5 * Matrix(group_.ad_matrix(e.theta[static_cast<std::size_t>(i)]));
    const Matrix dg = Matrix(field_->dg_matrix(group_, e.y[static_cast<std::size_t>(i)]));
    const Matrix left = identity() + half_ad, right = identity() - half_ad;
    return -0.5 * Matrix(group_.ad_matrix(e.w[static_cast<std::size_t>(i)])) + Matrix(Matrix(left * dg) * right);
  }
  Matrix identity() const {
    if constexpr (kSparseOperator<G>) {
      Matrix m(q_, q_);
      m.setIdentity();
      return m;
    } else {
      return Matrix::Identity(q_, q_);
    }
  }

  // Whether h ||F|| = r at k, the n-th iterate, is solved. The tolerance is relative to the step's own scale: h ||F||
  // is the error the stages leave in the step's increment u = h sum b_j K_j, so it is held below tol min(1, h ||K||)
  // (an absolute tol alone passes a good predictor at small h, and each step then keeps an error of about tol, which
  // sums to tol / h over a unit of time and flattens every method's order). The rounding floor excuses a residual
  // only once the iteration has worked on it (n > 0): a start within the floor but not within tol may carry a
  // systematic error (the predictor's), which would add up over the steps as rounding's noise does not. Where the
  // floor underestimates the noise (a field more sensitive than dg says), a residual within the absolute test
  // (within_absolute: max(tol, the conservative floor)) that has stopped halving, or the last iteration's, is solved
  // as well: rounding, not the method, then decides it.
  bool within_tolerance(double r, double before, const Eigen::VectorXd& k, const Evaluation& e, const SolverOptions& opt,
                        double kappa, int n, bool within_absolute, bool last) const {
    if (r <= opt.tol * std::min(1.0, h_ * k.norm())) return true;
    if (n == 0) return false;
    return r <= floor(e, kappa) || (within_absolute && (last || r > 0.5 * before));
  }

  // The rounding floor of h ||F||, the noise of its evaluation: F_i = K_i - dexpinv~_{Theta_i}(w_i) cancels two terms
  // of size ||w_i|| (1 + ||Theta_i||) to eps times that, times h; rounding eps (1 + ||Theta_i||) in
  // Y_i = y_k exp(Theta_i) moves w_i by ||dg|| times that, which h turns into kappa = h ||dg_{y_k}||_F (stiffness()).
  // A safety factor 64 sqrt(sq). It vanishes with h: the order holds down to the rounding of the step itself.
  double floor(const Evaluation& e, double kappa) const {
    double scale = 0.0;
    for (std::size_t i = 0; i < e.theta.size(); ++i)
      scale += (2.0 * h_ * e.w[i].norm() + kappa) * (1.0 + e.theta[i].norm());
    return kRoundingFactor * std::numeric_limits<double>::epsilon() * std::sqrt(double(size())) * scale;
  }
  // The floor with an absolute 1 in its scale, 64 eps sqrt(sq) (1 + sum ||Theta_i|| + h ||w_i||) (1 + kappa): an
  // upper bound of the noise whatever the field's scales, read only once the iteration has stopped improving.
  double conservative_floor(const Evaluation& e, double kappa) const {
    double scale = 1.0;
    for (std::size_t i = 0; i < e.theta.size(); ++i) scale += e.theta[i].norm() + h_ * e.w[i].norm();
    return kRoundingFactor * std::numeric_limits<double>::epsilon() * std::sqrt(double(size())) * scale * (1.0 + kappa);
  }
  static constexpr double kRoundingFactor = 64.0;

  G group_;
  VectorField<G>* field_;
  const integrators::Tableau* tab_;
  Element y_;
  double t_, h_;
  int q_;
  // dg_{y_k}, evaluated once per step: every solve's floor reads it.
  const Matrix& jacobian_at_start() const {
    if (!jacobian_at_start_) {
      field_->set_time(t_);
      jacobian_at_start_ = Matrix(field_->dg_matrix(group_, y_));
    }
    return *jacobian_at_start_;
  }
  const Spectrum& spectrum_at_start() const {
    if (!spectrum_at_start_) spectrum_at_start_.emplace(Eigen::MatrixXd(jacobian_at_start()));
    return *spectrum_at_start_;
  }
  mutable std::optional<Matrix> jacobian_at_start_;
  mutable std::optional<Spectrum> spectrum_at_start_;
};

// Whether the stages k_b at tau_b are the root continued from the root k_a at tau_a: the Krawczyk-type certificate
// of branch_certificate.hpp on the stacked system F(K, tau), with its exact Jacobian. Above kCertificateMaxDim the
// dense algebra would outweigh the step: the tests of the file comment decide alone.
template <LieGroup G>
bool certified_link(const RkmkStages<G>& sys, const Eigen::VectorXd& k_a, double tau_a, const Eigen::VectorXd& k_b,
                    double tau_b) {
  if (sys.size() > kCertificateMaxDim) return true;
  const auto at = [&](double tau, const Eigen::VectorXd& x, Eigen::VectorXd* f) {
    const RkmkStages<G> s = sys.at_step(tau);
    const auto e = s.evaluate(x);
    if (f) *f = e.f;
    return Eigen::MatrixXd(typename RkmkStages<G>::Matrix(s.jacobian(x, e, Differential::exact)));
  };
  const Eigen::VectorXd c = (k_a + k_b) / 2;
  BranchLink link{.x_a = k_a, .x_b = k_b, .tau_a = tau_a, .tau_b = tau_b, .d_a = at(tau_a, k_a, nullptr),
                  .d_b = at(tau_b, k_b, nullptr), .d_mid = {}, .f_mid = {}};
  const auto taus = BranchLink::taus(tau_a, tau_b);
  for (std::size_t i = 0; i < taus.size(); ++i) link.d_mid[i] = at(taus[i], c, &link.f_mid[i]);
  return certify_link(link).holds;
}

// The stages continued from h = 0 (see the file comment): the method's solve from its start (stiff: from K = 0,
// unless start_first), checked; else the branch followed from h = 0 and the method's solve at h from its root. The
// answer says whether its root passed the tangent's test (near_tangent), which a caller's next stiff step may take
// as start_first.
template <LieGroup G>
StageSolution continued_stages(const RkmkStages<G>& sys, const Eigen::VectorXd& start, Method method,
                               Differential d, const SolverOptions& opt,
                               const integrators::DecoupledNewtonMatrix* simplified = nullptr,
                               bool start_first = false) {
  constexpr int kMaxPathSteps = 400;
  constexpr double kPathTolerance = 1e-10;  // h ||F|| at the path's points before h
  constexpr double kStiff = 1.0;            // h ||dg_{y_k}||_F above which the step starts linearly implicit
  const bool stiff = method != Method::fixed_point && sys.stiffness() > kStiff;
  const Eigen::VectorXd root0 = sys.constant(sys.g_at_start());
  const Eigen::VectorXd tangent = sys.thetas(root0);
  // Whether a solve's root lies within acceptance_radius of the prediction (its Theta) it is checked against.
  const auto near = [&](const StageSolution& s, const Eigen::VectorXd& predicted) {
    return s.status == Status::converged &&
           (sys.thetas(s.k) - predicted).norm() <= acceptance_radius(predicted.norm());
  };
  int spent = 0, jacobians = 0, factorizations = 0;
  std::optional<Factorization> factored;
  const auto count = [&](const StageSolution& s) {
    spent += s.iterations;
    jacobians += s.jacobian_evaluations;
    factorizations += s.factorizations;
    factored = widest(factored, s.factorization);
  };
  const auto accepted = [&](StageSolution s) {
    s.iterations += spent;
    s.jacobian_evaluations += jacobians;
    s.factorizations += factorizations;
    s.factorization = widest(s.factorization, factored);
    s.continued = true;
    s.near_tangent = near(s, tangent);
    return s;
  };
  StageSolution first;
  // A root must also be certified continued from h = 0 (certified_link), unless the step is dissipative: h |Re mu|
  // at least kDissipative for an eigenvalue of dg_{y_k}, where no fixed matrix contracts over [0, h] and the
  // linearisation's argument decides (docs/continuation.md). A stiff field that merely turns fast is certified.
  const bool dissipative = stiff && sys.dissipative();
  const auto on_branch = [&](const StageSolution& s) {
    return dissipative || certified_link(sys, root0, 0.0, s.k, sys.h());
  };
  const auto from_start = [&] {
    first = sys.solve(start, method, d, opt, simplified);
    return near(first, tangent) && on_branch(first);
  };
  const bool tried = !stiff || (start_first && !start.isZero(0.0));
  if (tried && from_start()) return accepted(std::move(first));
  if (stiff && sys.linearisation_regular()) {
    if (tried) count(first);
    first = sys.solve(Eigen::VectorXd::Zero(sys.size()), method, d, opt, simplified);
    if (near(first, sys.thetas(first.first_iterate)) && on_branch(first)) return accepted(std::move(first));
  } else if (!tried && from_start()) {
    return accepted(std::move(first));
  }
  count(first);
  SolverOptions corrector = opt;  // the path's points need not be solved to the request's tol, only its end
  corrector.max_iterations = kMaxCorrectorIterations;
  corrector.tol = std::max(opt.tol, kPathTolerance);
  double tau = 0.0, dtau = sys.h();
  Eigen::VectorXd k = root0, slope = sys.slope_at_zero();
  for (int p = 0; p < kMaxPathSteps && tau < sys.h(); ++p) {
    throw_if_cancelled();
    const double next = std::min(sys.h(), tau + dtau);
    const RkmkStages<G> at = sys.at_step(next);
    const Eigen::VectorXd pred = k + (next - tau) * slope;
    const StageSolution c = at.solve(pred, Method::newton_group, Differential::exact, corrector);
    count(c);
    const double move = (at.thetas(pred) - sys.at_step(tau).thetas(k)).norm();
    if (c.status == Status::converged && (at.thetas(c.k) - at.thetas(pred)).norm() <= acceptance_radius(move) &&
        (move <= kUncertifiedMove || dissipative || certified_link(sys, k, tau, c.k, next))) {
      slope = (c.k - k) / (next - tau);
      k = c.k;
      tau = next;
      dtau *= c.iterations <= 2 ? 2.0 : c.iterations <= 4 ? 1.0 : 0.5;  // as continuation.hpp's path
    } else if ((dtau /= 2) < 1e-10 * sys.h()) {
      break;
    }
  }
  if (tau < sys.h()) {
    first.iterations = spent;
    first.jacobian_evaluations = jacobians;
    first.factorizations = factorizations;
    first.factorization = factored;
    first.reason = "the stages' branch from h = 0 could not be followed past h = " + format_number(tau) +
                   " (a fold, or too stiff a turn); the method from its start: " + first.reason;
    if (first.status == Status::converged) first.status = Status::fold;
    return first;
  }
  StageSolution last = sys.solve(k, method, d, opt, simplified);
  last.iterations += spent;
  last.jacobian_evaluations += jacobians;
  last.factorizations += factorizations;
  last.factorization = widest(last.factorization, factored);
  const Eigen::VectorXd theta = sys.thetas(k);
  last.continued = last.status == Status::converged &&
                   (sys.thetas(last.k) - theta).norm() <= 1e-6 * (1.0 + theta.norm());
  last.near_tangent = last.continued && near(last, tangent);
  if (last.status == Status::converged && !last.continued) {
    last.status = Status::fold;
    last.reason = "the method left the stages' root continued from h = 0: " + last.reason;
  }
  return last;
}

}  // namespace lienewton
