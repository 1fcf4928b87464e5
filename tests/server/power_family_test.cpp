// k rigid bodies by name over HTTP: "group": "SExR^k" with "n": k (and the shorthand "SExR^5"). A user's field that
// moves each body by its own twist leaves the bodies independent, so each body of the k-body solve is the one-body
// solve on SExR from that body's z; the answer says which factorization it used (4 bodies, 48 unknowns: dense LU;
// 13 bodies, 156: sparse LU), and an integration runs through both implicit integrators. n is bounded per family.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <string>
#include <utility>

#include "core/groups/mechanics_groups.hpp"
#include "server/json_codec.hpp"
#include "test_server.hpp"

namespace lienewton::service {
namespace {

class PowerFamilyRoutes : public testing::SharedServerTest {};
using testing::matrix_from_rows;

// Appended piece by piece: "literal" + std::string trips a false -Wrestrict in GCC 12 at -O3.
template <class... Parts>
std::string cat(const Parts&... parts) {
  std::string out;
  ((out += parts), ...);
  return out;
}

// Body i's twist field (group_registry_test.cpp's SExR program) at rows and columns 11 i + 1 ... 11 i + 11.
std::string body_block(int i) {
  const auto at = [&](int r) { return std::to_string(11 * i + r); };
  return cat("v = y(", at(5), ":", at(10), ",", at(11), "); a = -0.5 * v + 0.2 * sin(y(", at(1), ":", at(6), ",",
             at(4), ")); X = [0 -v(3) v(2) v(4); v(3) 0 -v(1) v(5); -v(2) v(1) 0 v(6); 0 0 0 0]; B",
             std::to_string(i), " = [X zeros(4,7); zeros(7,4) [zeros(6) a; zeros(1,7)]]; ");
}
// The k bodies' fields side by side: g = diag(B0, ..., B(k-1)).
std::string program(int k) {
  std::string p;
  for (int i = 0; i < k; ++i) p += body_block(i);
  p += "g = [";
  for (int i = 0; i < k; ++i) {
    if (i > 0) p += cat("; zeros(11,", std::to_string(11 * i), ") ");
    p += cat("B", std::to_string(i));
    if (i + 1 < k) p += cat(" zeros(11,", std::to_string(11 * (k - 1 - i)), ")");
  }
  p += "]";
  return p;
}

std::string rows_of(const Eigen::MatrixXd& m) {
  std::string out = "[";
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    out += r ? ",[" : "[";
    for (Eigen::Index c = 0; c < m.cols(); ++c) {
      if (c) out += ",";
      out += json(m(r, c)).dump();  // round-trip precision
    }
    out += "]";
  }
  out += "]";
  return out;
}

TEST_F(PowerFamilyRoutes, EachBodyOfTheSolveIsItsOwnSolve) {
  for (const auto& [k, solver] : {std::pair{4, "dense-lu"}, std::pair{13, "sparse-lu"}}) {
    const SE3xR6PowerGroup group(k);
    const Eigen::MatrixXd z = group.matrix(group.random(7));
    const std::string group_field = k == 4 ? R"("group":"SExR^k","n":4)" : R"("group":"SExR^13")";
    const json all =
        post("/api/v1/solve", cat("{", group_field, R"(,"h":0.5,"tol":1e-12,"z":)", rows_of(z), R"(,"g":")", program(k),
                                  R"("})"));
    ASSERT_EQ(all["status"], "converged") << all.dump().substr(0, 400);
    EXPECT_EQ(all["linear_solver"], solver) << k;
    const Eigen::MatrixXd y = matrix_from_rows(all["y"]);
    ASSERT_EQ(y.rows(), 11);  // the bodies side by side; the program reads and writes diag(y1, ..., yk)
    ASSERT_EQ(y.cols(), 11 * k);
    for (int i = 0; i < k; ++i) {
      const json one = post("/api/v1/solve", cat(R"({"group":"SExR","h":0.5,"tol":1e-12,"z":)",
                                                 rows_of(z.middleCols(11 * i, 11)), R"(,"g":")", program(1),
                                                 R"("})"));
      ASSERT_EQ(one["status"], "converged") << i;
      EXPECT_EQ(one["linear_solver"], "dense-lu");
      EXPECT_LE((y.middleCols(11 * i, 11) - matrix_from_rows(one["y"])).norm(), 1e-10) << "body " << i;
    }
  }
}

TEST_F(PowerFamilyRoutes, BothImplicitIntegratorsStepTheBodies) {
  // dirk-cg2 factors one stage's 48 unknowns, rkmk-radau3 (exact differential, the default) its coupled 3-stage
  // system of 144: both at most kDenseLuMaxDim, so densely.
  for (const char* integrator : {"dirk-cg2", "rkmk-radau3"}) {
    const json r = post("/api/v1/integrate", cat(R"({"group":"SExR^k","n":4,"h":0.1,"t_end":0.3,"integrator":")",
                                                 std::string(integrator), R"(","g":")", program(4), R"("})"));
    ASSERT_EQ(r["status"], "converged") << integrator << " " << r.dump().substr(0, 400);
    EXPECT_EQ(r["linear_solver"], "dense-lu") << integrator;
    EXPECT_EQ(r["y"].size(), 11u);
    EXPECT_EQ(r["y"][0].size(), 44u);
  }
}

TEST_F(PowerFamilyRoutes, TheBodyCountIsBoundedAndNamed) {
  const json many = post("/api/v1/solve", R"({"group":"SExR^k","n":129,"h":0.5})", 422);
  EXPECT_EQ(many["error"]["field"], "n");
  EXPECT_NE(many["error"]["message"].get<std::string>().find("from 2 to 128"), std::string::npos) << many.dump();
  const json none = post("/api/v1/solve", R"({"group":"SExR^0","h":0.5})", 422);
  EXPECT_EQ(none["error"]["field"], "group");
  const json clash = post("/api/v1/solve", R"({"group":"SExR^8","n":4,"h":0.5})", 422);
  EXPECT_EQ(clash["error"]["field"], "n");
  const json paper = post("/api/v1/solve", R"({"group":"SExR^k","n":2,"h":0.5,"problem":"paper-linear"})", 422);
  EXPECT_EQ(paper["error"]["field"], "group");  // the paper's matrix problems are not defined on strips of bodies
}

}  // namespace
}  // namespace lienewton::service
