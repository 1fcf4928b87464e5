// The chain integrated by lienewton's implicit Lie-group integrators, through the whole request path (validation,
// the SExR^k family, integrate_on on (SE(3) x R^6)^k with sparse Newton matrices), against the independent
// flat-coordinate RK4 reference (chain_flat_reference.hpp, itself checked in chain_test.cpp): the state at t = 1.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cstdio>
#include <string>

#include "core/chain.hpp"
#include "core/integrate.hpp"
#include "core/solvers/continuation.hpp"
#include "tests/core/chain_flat_reference.hpp"

namespace lienewton {
namespace {

// The Release suite's: under ASan k = 2 alone takes about 3 minutes.
#if !defined(LIENEWTON_SANITIZED)
// The soft chain of the reference (k_s = 1e3, c = 20: rates up to ~125 1/s), which RK4 resolves to ~1e-12 in 20000
// steps; the default chain's stiffness is the integrators' business, not the reference's.
ChainParams soft() {
  ChainParams p;
  p.stiffness = 1e3;
  p.damping = 20.0;
  return p;
}

IntegrateRequest chain_request(int k, Integrator integrator, double h) {
  IntegrateRequest req;
  req.problem.kind = ProblemKind::chain;
  req.problem.group = "SExR^k";
  req.problem.n = k;
  req.problem.chain = soft();
  req.integrator = integrator;
  req.h = h;
  req.solver.tol = 1e-12;
  req.reference = false;
  return req;
}

// The errors at t = 1 at steps h and h/2 against the reference, and the two states.
struct Halving {
  double coarse, fine;
  Eigen::MatrixXd y_coarse, y_fine;
};
Halving halving(int k, Integrator integrator, double h, const SE3xR6PowerGroup::Element& reference) {
  Halving out;
  for (double step : {h, h / 2}) {
    const std::string name = std::string(to_string(integrator)) + " at k = " + std::to_string(k);
    const IntegrateResult r = integrate(chain_request(k, integrator, step));
    EXPECT_EQ(r.status, Status::converged) << name << ": " << r.reason;
    const Eigen::MatrixXd y = SE3xR6PowerGroup(k).element(r.y);
    const double error = (y - reference).norm();
    std::printf("%s, h = 2^%d: ||Y - Y_rk4||_F = %.2e\n", name.c_str(), std::ilogb(step), error);
    (step == h ? out.coarse : out.fine) = error;
    (step == h ? out.y_coarse : out.y_fine) = y;
  }
  return out;
}

// rkmk-radau3 (order 5) at h = 2^-9 is within 1e-8 of the reference (2.8e-9 at k = 8 when written) and its error
// falls 32-fold from 2^-8 (within 25%: at k = 2 the finer error, 3e-11, carries a few 1e-12 of the stages' rounding
// floor summed over 512 steps, and where a stage starts moves it); dirk-cg2 (order 2) falls 4-fold from 2^-12 to 2^-13, and its Richardson extrapolation
// (4 Y(h/2) - Y(h)) / 3 is within 1e-8 (5e-9 at k = 8): both converge to the flat reference's solution at their orders.
constexpr int kChainLengths[] = {2, 4, 8};
TEST(ChainIntegrators, DirkAndRadauConvergeToTheFlatRk4ReferenceAtTheirOrders) {
  for (int k : kChainLengths) {
    const Chain chain{soft()};
    const test::FlatChain flat(soft(), k);
    const SE3xR6PowerGroup::Element reference = flat.strip(flat.rk4(flat.flat(chain.start_strip(k)), 1.0, 20000));
    const Halving radau = halving(k, Integrator::rkmk_radau3, 1.0 / 256, reference);
    EXPECT_LE(radau.fine, 1e-8) << "k " << k;
    EXPECT_NEAR(radau.coarse / radau.fine, 32.0, 8.0) << "k " << k;
    const Halving dirk = halving(k, Integrator::dirk_cg2, 1.0 / 4096, reference);
    EXPECT_NEAR(dirk.coarse / dirk.fine, 4.0, 0.4) << "k " << k;
    const double extrapolated = ((4 * dirk.y_fine - dirk.y_coarse) / 3 - reference).norm();
    std::printf("dirk-cg2 at k = %d extrapolated: %.2e\n", k, extrapolated);
    EXPECT_LE(extrapolated, 1e-8) << "k " << k;
  }
}
#endif

// At the default data the joints make the chain stiff (h ||dg|| ~ 10^3 at h = 2^-8): a stage's residual cannot get
// below ~1e-12 (k = 8) ... 3e-11 (k = 128), above tol = 1e-13, and is there after two Newton iterations from the
// explicit Lie-Euler prediction. Each stage stops there (SolverOptions::stop_at_rounding) instead of spending
// iterations on the stall rule: two per stage, four per dirk-cg2 step after the first, at any number of bodies. The
// first step, from rest, finds its first stage's root too far from the tangent's prediction to accept it and starts
// again from the linearly implicit value (continuation.hpp): at most six, where following the branch took 8 to 11.
// Up to 32 coordinates (k <= 2) the tangent's root must also pass the branch certificate (docs/continuation.md),
// which these stiff spring modes defeat at this step: each stage is then solved again from its linearly implicit
// value, twice the iterations.
TEST(ChainIntegrators, DirkStagesStopWhereRoundingLeavesThem) {
  for (int k : {2, 8, 32, 128}) {
    IntegrateRequest req;
    req.problem.kind = ProblemKind::chain;
    req.problem.group = "SExR^k";
    req.problem.n = k;
    req.integrator = Integrator::dirk_cg2;
    req.h = 1.0 / 256;
    req.t_end = 16.0 / 256;
    req.reference = false;
    const IntegrateResult r = integrate(req);
    ASSERT_EQ(r.status, Status::converged) << "k " << k << ": " << r.reason;
    ASSERT_EQ(r.steps.size(), 16u);
    const int per_step = 12 * k <= kCertificateMaxDim ? 8 : 4;  // SE(3) x R^6: 12 coordinates a body
    EXPECT_LE(r.steps[0].iterations, per_step + 2) << "k " << k;
    for (std::size_t i = 1; i < r.steps.size(); ++i) {
      EXPECT_LE(r.steps[i].iterations, per_step) << "k " << k << ", step " << i;
      EXPECT_LE(r.steps[i].residual, 1e-9) << "k " << k << ", step " << i;
    }
  }
}

}  // namespace
}  // namespace lienewton
