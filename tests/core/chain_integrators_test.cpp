// The chain integrated by lienewton's implicit Lie-group integrators, through the whole request path (validation,
// the SExR^k family, integrate_on on (SE(3) x R^6)^k with sparse Newton matrices), against the independent
// flat-coordinate RK4 reference (chain_flat_reference.hpp, itself checked in chain_test.cpp): the state at t = 1.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cstdio>
#include <string>

#include "core/chain.hpp"
#include "core/integrate.hpp"
#include "tests/core/chain_flat_reference.hpp"

namespace lienewton {
namespace {

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

struct Run {
  Integrator integrator;
  double h;
};

TEST(ChainIntegrators, DirkAndRadauMatchTheFlatRk4ReferenceAtTimeOne) {
  for (int k : {2, 4, 8}) {
    const Chain chain{soft()};
    const test::FlatChain flat(soft(), k);
    const SE3xR6PowerGroup::Element reference = flat.strip(flat.rk4(flat.flat(chain.start_strip(k)), 1.0, 20000));
    for (const Run& run : {Run{Integrator::dirk_cg2, 1.0 / 16384}, Run{Integrator::rkmk_radau3, 1.0 / 128}}) {
      const std::string name = std::string(to_string(run.integrator)) + " at k = " + std::to_string(k);
      const IntegrateResult r = integrate(chain_request(k, run.integrator, run.h));
      ASSERT_EQ(r.status, Status::converged) << name << ": " << r.reason;
      const double error = (SE3xR6PowerGroup(k).element(r.y) - reference).norm();
      std::printf("%s, h = 2^%d: ||Y - Y_rk4||_F = %.2e\n", name.c_str(), std::ilogb(run.h), error);
      EXPECT_LE(error, 1e-8) << name;
    }
  }
}

}  // namespace
}  // namespace lienewton
