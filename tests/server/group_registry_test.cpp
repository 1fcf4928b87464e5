// A group reaches every request by name: the additive group of n x n matrices (tests/core/matrix_sum_group.hpp),
// registered by one line in its header, answers an HTTP solve, sweep and basin map asked for with
// "group": "Rnxn". On it Newton is classical Newton, so each answer is checked against f(y) = y - z - h g(y)
// computed here from the problem's formula, independently of the solvers.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <set>
#include <string>

#include "core/group_registry.hpp"
#include "server/json_codec.hpp"
#include "test_server.hpp"
#include "tests/core/matrix_sum_group.hpp"

namespace lienewton::service {
namespace {

class GroupRoutes : public testing::SharedServerTest {
 protected:
  static json post(const std::string& path, const std::string& body, int status = 200) {
    auto res = server_->client().Post(path, body, "application/json");
    EXPECT_TRUE(res);
    if (!res) return json();
    EXPECT_EQ(res->status, status) << res->body;
    return json::parse(res->body);
  }
};

Eigen::MatrixXd matrix(const json& rows) {
  Eigen::MatrixXd m(rows.size(), rows[0].size());
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (std::size_t j = 0; j < rows[i].size(); ++j) m(i, j) = rows[i][j].get<double>();
  return m;
}

// paper-linear's g, written out: the superdiagonal of y and its negative below.
Eigen::MatrixXd paper_linear(const Eigen::MatrixXd& y) {
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(y.rows(), y.cols());
  for (Eigen::Index i = 0; i + 1 < y.rows(); ++i) g(i, i + 1) = y(i, i + 1), g(i + 1, i) = -y(i, i + 1);
  return g;
}

// The implicit Euler residual on the additive group: log(z^-1 y) - h g(y) = y - z - h g(y).
double truth(const Eigen::MatrixXd& y, const Eigen::MatrixXd& z, double h) {
  return (y - z - h * paper_linear(y)).norm();
}

TEST_F(GroupRoutes, TheRegistryListsTheTestGroupAfterSO) {
  const auto names = registered_group_names();
  ASSERT_GE(names.size(), 2u);
  EXPECT_EQ(names.front(), "SO");
  EXPECT_EQ(std::set<std::string>(names.begin(), names.end()).count(MatrixSumFamily::kName), 1u);
}

TEST_F(GroupRoutes, SolveIsClassicalNewtonOnTheAdditiveGroup) {
  const std::string z = "[[0.5,-1,2],[0.25,3,-0.5],[1,0,-2]]";
  for (const char* method : {"newton-group", "newton-algebra"}) {
    const json r = post("/api/v1/solve", R"({"group":"Rnxn","problem":"paper-linear","n":3,"h":0.75,"method":")" +
                                             std::string(method) + R"(","differential":"exact","z":)" + z + "}");
    EXPECT_EQ(r["status"], "converged") << method;
    // f is affine in y: the exact Newton step lands on the root, to rounding.
    EXPECT_EQ(r["iterations"], 1) << method;
    EXPECT_LE(truth(matrix(r["y"]), matrix(json::parse(z)), 0.75), 1e-13) << method;
    EXPECT_EQ(r["trace"][0]["angle"], 0.0);
    EXPECT_TRUE(r["trace"][0]["distance_to_pi"].is_null());  // an unbounded log: no boundary to be near
  }
}

TEST_F(GroupRoutes, SweepCellsConvergeInOneNewtonStep) {
  const json s = post("/api/v1/sweep", R"({"group":"Rnxn","problem":"paper-linear","methods":["newton-group",)"
                                       R"("newton-algebra"],"differential":"exact","n":[2,4],"h":[0.25,2]})");
  ASSERT_EQ(s["cells"].size(), 8u);
  for (const json& c : s["cells"]) {
    EXPECT_EQ(c["status"], "converged") << c.dump();
    EXPECT_EQ(c["iterations"], 1) << c.dump();
    EXPECT_LE(c["residual"].get<double>(), 1e-13) << c.dump();
  }
}

TEST_F(GroupRoutes, BasinMapFindsTheOneRootFromEveryStart) {
  const json map = post("/api/v1/basins", R"({"group":"Rnxn","problem":"paper-linear","n":3,"h":0.5,)"
                                          R"("methods":["newton-group","newton-algebra"],"size":5,"r":2})");
  EXPECT_TRUE(map["complete"].get<bool>());
  ASSERT_EQ(map["roots"].size(), 1u);  // y - h g(y) = z is linear and regular: one root
  const Eigen::MatrixXd z = matrix(map["grid"]["z"]);
  EXPECT_LE(truth(matrix(map["roots"][0]["y"]), z, 0.5), 1e-13);
  for (const json& m : map["methods"]) EXPECT_EQ(m["converged"], 25) << m.dump();
  // Its log radius is infinite, so a map needs an explicit r.
  const json no_r = post("/api/v1/basins", R"({"group":"Rnxn","n":3,"size":5})", 400);
  EXPECT_EQ(no_r["error"]["field"], "r");
}

TEST_F(GroupRoutes, GroupsAndTheirProblemsAreCheckedByName) {
  const json unknown = post("/api/v1/solve", R"({"group":"SE"})", 422);
  EXPECT_EQ(unknown["error"]["field"], "group");
  const std::string message = unknown["error"]["message"];
  EXPECT_NE(message.find("SO"), std::string::npos) << message;
  EXPECT_NE(message.find(MatrixSumFamily::kName), std::string::npos) << message;
  const json rigid = post("/api/v1/solve", R"({"group":"Rnxn","problem":"rigid-body","n":3})", 422);
  EXPECT_EQ(rigid["error"]["field"], "group");
  const json not_a_string = post("/api/v1/solve", R"({"group":3})", 400);
  EXPECT_EQ(not_a_string["error"]["field"], "group");
  // The default group answers as before; naming it changes nothing.
  const json so = post("/api/v1/solve", R"({"group":"SO","n":3,"h":0.5})");
  const json plain = post("/api/v1/solve", R"({"n":3,"h":0.5})");
  EXPECT_EQ(so["y"], plain["y"]);
  EXPECT_EQ(so["trace"].size(), plain["trace"].size());
}

// GET forms read group= like any other parameter.
TEST_F(GroupRoutes, QueryParametersNameTheGroup) {
  std::string body;
  auto res = server_->client().Get("/api/v1/solve/events?group=Rnxn&problem=paper-linear&n=2&h=0.5&differential=exact",
                                   [&](const char* data, size_t n) {
                                     body.append(data, n);
                                     return true;
                                   });
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 200) << body;
  const auto last = body.rfind("event: result\ndata: ");
  ASSERT_NE(last, std::string::npos) << body;
  const json result = json::parse(body.substr(last + 20));
  EXPECT_EQ(result["status"], "converged");
  EXPECT_EQ(result["iterations"], 1);
}

}  // namespace
}  // namespace lienewton::service
