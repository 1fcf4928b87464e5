// The solvers on (SO(3) x R^3)^k (power_group.hpp), before any family serves it: with a field that couples no
// bodies, the implicit Euler equation of k heavy tops is k independent equations, so one Newton solve on the power
// group must land where k solves on SO(3) x R^3 land. It shows the solvers take PowerGroup's run-time sizes as they
// are (they are instantiated here; registering the family would compile them once in core).
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "core/groups/mechanics_groups.hpp"
#include "core/problems.hpp"
#include "core/solvers/run_method.hpp"

namespace lienewton {
namespace {

using G = SO3xR3PowerGroup;
using Body = SO3xR3Group;

// Body i of an element (the strip of body matrices, as the solvers return it).
Body::Element body_block(const Eigen::MatrixXd& y, int i) { return y.middleCols<7>(7 * i); }

// Every body moved by one body field on its own block: dg is block diagonal.
class EveryBody final : public VectorField<G> {
 public:
  EveryBody(const G& group, const VectorField<Body>& body) : k_(group.bodies()), body_(body) {}
  Vector g(const Element& y) const override {
    Vector out(6 * k_);
    for (int i = 0; i < k_; ++i) out.segment<6>(6 * i) = body_.g(body_block(y, i));
    return out;
  }
  Vector dg(const Element& y, const Vector& u) const override {
    Vector out(6 * k_);
    for (int i = 0; i < k_; ++i) out.segment<6>(6 * i) = body_.dg(body_block(y, i), u.segment<6>(6 * i));
    return out;
  }

 private:
  int k_;
  const VectorField<Body>& body_;
};

// Newton on the group (version 1) and on the algebra (version 2), k = 4 heavy tops from the seeded poses: each body
// of the joint root is the single body's root to 1e-10 (both solved to tol 1e-12), and stays on the group.
TEST(PowerGroupSolve, ImplicitEulerOnUncoupledBodiesIsOneSolvePerBody) {
  const int k = 4;
  const double h = 0.1;
  const G group(k);
  const Body body;
  const auto top = make_field(body, ProblemKind::heavy_top, RigidBodyParams{}, HeavyTopParams{});
  const EveryBody field(group, *top);
  const G::Element z = group.random(17);
  SolverOptions opt;
  opt.tol = 1e-12;
  const auto eq = Equation<G>::implicit_euler(group, z, h, field);
  for (const SolveResult& all : {newton_group(eq, opt), newton_algebra(eq, opt)}) {
    ASSERT_EQ(all.status, Status::converged);
    EXPECT_LE(group.defect(all.y), 1e-12);
    for (int i = 0; i < k; ++i) {
      const SolveResult one = newton_group(Equation<Body>::implicit_euler(body, body_block(z, i), h, *top), opt);
      ASSERT_EQ(one.status, Status::converged) << "body " << i;
      EXPECT_LE((body_block(all.y, i) - one.y).norm(), 1e-10) << "body " << i;
    }
  }
}

}  // namespace
}  // namespace lienewton
