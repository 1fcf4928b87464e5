// The chain written by a user as a program on (SE(3) x R^6)^k: y is diag(y_1, ..., y_k) and each link's block is
// addressed by its rows and columns, g returned as diag(g_1, ..., g_k). The program is written here from the
// model's equations (docs/requests.md, the chain), term by term in the built-in's order, and must answer as the
// built-in does: an integration's y within 1e-12 and its Newton iterations within 1, at the default (stiff) data.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/chain.hpp"
#include "core/integrate.hpp"
#include "core/solve.hpp"

namespace lienewton {
namespace {

// Rows or columns first ... first + count - 1 (1-based) as a program's range.
std::string span(int first, int count) { return std::to_string(first) + ":" + std::to_string(first + count - 1); }

// The program of k default links: link i's block starts at row and column 11 (i - 1) + 1; R, x, w, v as in
// core/chain.cpp; joint j ties link j - 1's bottom (the origin for j = 1) to link j's top with the force f_j.
std::string chain_program(int k) {
  std::string s;
  for (int i = 1; i <= k; ++i) {
    const int o = 11 * (i - 1);
    const std::string n = std::to_string(i);
    s += "R" + n + " = y(" + span(o + 1, 3) + "," + span(o + 1, 3) + "); x" + n + " = y(" + span(o + 1, 3) + "," +
         std::to_string(o + 4) + "); w" + n + " = y(" + span(o + 5, 3) + "," + std::to_string(o + 11) + "); v" + n +
         " = y(" + span(o + 8, 3) + "," + std::to_string(o + 11) + ");\n";
  }
  for (int j = 1; j <= k; ++j) {
    const std::string n = std::to_string(j), u = std::to_string(j - 1);
    std::string gap = "x" + n + " + R" + n + "*at", rate = "R" + n + "*(v" + n + " + cross(w" + n + ", at))";
    if (j > 1) {
      gap = "(" + gap + ") - (x" + u + " + R" + u + "*ab)";
      rate += " - R" + u + "*(v" + u + " + cross(w" + u + ", ab))";
    }
    s += "f" + n + " = -ks*(" + gap + ") - c*(" + rate + ");\n";
  }
  std::string g;
  for (int i = 1; i <= k; ++i) {
    const std::string n = std::to_string(i), below = std::to_string(i + 1);
    // The link's own terms, then joint i's push at its top, then joint i + 1's pull at its bottom.
    s += "b" + n + " = R" + n + "'*f" + n + ";\n";
    std::string dw = "cross(J.*w" + n + ", w" + n + ")./J + cross(at, b" + n + ")./J";
    std::string dv = "cross(v" + n + ", w" + n + ") + R" + n + "'*gam + b" + n + "/m";
    if (i < k) {
      s += "p" + n + " = R" + n + "'*(-f" + below + ");\n";
      dw += " + cross(ab, p" + n + ")./J";
      dv += " + p" + n + "/m";
    }
    s += "W" + n + " = [0 -w" + n + "(3) w" + n + "(2); w" + n + "(3) 0 -w" + n + "(1); -w" + n + "(2) w" + n +
         "(1) 0];\n";
    s += "g" + n + " = [[W" + n + " v" + n + "; zeros(1,4)] zeros(4,7); zeros(7,4) [zeros(6) [" + dw + "; " + dv +
         "]; zeros(1,7)]];\n";
    g += "zeros(11," + std::to_string(11 * (i - 1)) + ") g" + n + " zeros(11," + std::to_string(11 * (k - i)) + ")" +
         (i < k ? "; " : "");
  }
  return s + "g = [" + g + "]";
}

ProblemSpec as_program(int k) {
  const ChainParams p;
  ProblemSpec spec{.group = "SExR^k", .n = k};
  spec.g = chain_program(k);
  spec.parameters = {{"J", p.inertia},
                     {"m", Eigen::MatrixXd::Constant(1, 1, p.mass)},
                     {"ks", Eigen::MatrixXd::Constant(1, 1, p.stiffness)},
                     {"c", Eigen::MatrixXd::Constant(1, 1, p.damping)},
                     {"gam", p.gravity},
                     {"at", Eigen::Vector3d(0, 0, 0.5 * p.length)},
                     {"ab", Eigen::Vector3d(0, 0, -0.5 * p.length)}};
  spec.z = Chain{p}.start(k);
  return spec;
}

TEST(ChainProgram, AnswersAsTheBuiltIn) {
  for (int k : {2, 3}) {
    for (Integrator integrator : {Integrator::dirk_cg2, Integrator::rkmk_radau3}) {
      IntegrateRequest built_in;
      built_in.problem = ProblemSpec{.kind = ProblemKind::chain, .group = "SExR^k", .n = k};
      built_in.integrator = integrator;
      built_in.h = 1.0 / 256;
      built_in.t_end = 16.0 / 256;
      built_in.reference = false;
      IntegrateRequest user = built_in;
      user.problem = as_program(k);
      const IntegrateResult a = integrate(built_in), b = integrate(user);
      const std::string name = std::string(to_string(integrator)) + " at k = " + std::to_string(k);
      ASSERT_EQ(a.status, Status::converged) << name << ": " << a.reason;
      ASSERT_EQ(b.status, Status::converged) << name << ": " << b.reason;
      std::printf("%s: |y - y_program| = %.1e, iterations %d and %d\n", name.c_str(), (a.y - b.y).cwiseAbs().maxCoeff(),
                  a.total_iterations, b.total_iterations);
      EXPECT_LE((a.y - b.y).cwiseAbs().maxCoeff(), 1e-12) << name;
      EXPECT_LE(std::abs(a.total_iterations - b.total_iterations), 1) << name;
    }
    SolveRequest built_in;
    built_in.problem = ProblemSpec{.kind = ProblemKind::chain, .group = "SExR^k", .n = k};
    built_in.h = 1.0 / 256;
    SolveRequest user = built_in;
    user.problem = as_program(k);
    const SolveResult a = solve(built_in), b = solve(user);
    ASSERT_TRUE(is_root(a)) << a.reason;
    ASSERT_TRUE(is_root(b)) << b.reason;
    EXPECT_LE(std::abs(a.total_iterations() - b.total_iterations()), 1) << "k " << k;
    EXPECT_LE((a.y - b.y).cwiseAbs().maxCoeff(), 1e-12) << "k " << k;
  }
}

}  // namespace
}  // namespace lienewton
