// NDJSON and SSE streams: records arrive as computed, end with one terminal record, agree with the plain
// answer; a client that leaves cancels its solve within an iteration or two.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

#include "server/json_codec.hpp"
#include "test_server.hpp"

namespace lienewton::service {
namespace {

using testing::post_lines;
using testing::TestServer;

const std::string kSolve = R"({"problem":"paper-sine","n":5,"h":0.5,"method":"newton-algebra","differential":"finite-difference","seed":7})";

TEST(HttpStreams, NdjsonSolveAgreesWithThePlainResult) {
  TestServer s;
  auto c = s.client();
  auto plain = c.Post("/api/v1/solve", kSolve, "application/json");
  ASSERT_TRUE(plain);
  ASSERT_EQ(plain->status, 200);
  const json expected = json::parse(plain->body);

  std::vector<json> records;
  auto res = post_lines(c, "/api/v1/solve", kSolve, "application/x-ndjson", [&](const std::string& line) {
    records.push_back(json::parse(line));
    return true;
  });
  ASSERT_TRUE(res);
  EXPECT_EQ(res->get_header_value("Content-Type"), "application/x-ndjson");
  EXPECT_TRUE(res->get_header_value("Content-Encoding").empty());
  ASSERT_GE(records.size(), 2u);
  EXPECT_EQ(records.back()["type"], "result");
  for (std::size_t k = 0; k + 1 < records.size(); ++k) {
    EXPECT_EQ(records[k]["type"], "iteration");
    EXPECT_EQ(records[k]["iteration"], static_cast<int>(k));
  }
  const json& result = records.back();
  EXPECT_EQ(result["status"], expected["status"]);
  EXPECT_EQ(result["iterations"], expected["iterations"]);
  EXPECT_EQ(result["y"], expected["y"]);  // deterministic: bit-identical
  ASSERT_EQ(result["trace"].size(), records.size() - 1);
  for (std::size_t k = 0; k + 1 < records.size(); ++k) {
    EXPECT_EQ(records[k]["residual"], expected["trace"][k]["residual"]);
    EXPECT_EQ(records[k]["step"], expected["trace"][k]["step"]);
  }
}

TEST(HttpStreams, IterationRecordsArriveBeforeTheSolveEnds) {
  // Each iteration waits 30 ms on the server; the first record must reach us long before the result.
  ServerOptions o;
  o.on_progress = [](int) { std::this_thread::sleep_for(std::chrono::milliseconds(30)); };
  TestServer s(o);
  auto c = s.client();
  const auto start = std::chrono::steady_clock::now();
  double first = -1, last = -1;
  auto res = post_lines(c, "/api/v1/solve", R"({"n":3,"h":0.5,"method":"fixed-point"})", "application/x-ndjson",
                        [&](const std::string& line) {
                          const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
                          if (first < 0) first = t;
                          if (json::parse(line)["type"] == "result") last = t;
                          return true;
                        });
  ASSERT_TRUE(res);
  ASSERT_GT(last, 0);
  EXPECT_LT(first, last - 0.1);
}

TEST(HttpStreams, ServerSentEvents) {
  TestServer s;
  auto c = s.client();
  std::string body;
  auto res = c.Get("/api/v1/solve/events?problem=paper-linear&n=3&h=0.5&method=newton-group&differential=exact&seed=1",
                   [&](const char* data, size_t n) {
                     body.append(data, n);
                     return true;
                   });
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 200);
  EXPECT_EQ(res->get_header_value("Content-Type"), "text/event-stream");
  EXPECT_EQ(body.rfind("event: iteration\ndata: {\"type\":\"iteration\"", 0), 0u) << body.substr(0, 80);
  const auto last = body.rfind("event: result\ndata: ");
  ASSERT_NE(last, std::string::npos);
  const json result = json::parse(body.substr(last + 20));
  EXPECT_EQ(result["status"], "converged");
}

// A POST route asked for Server-Sent Events alone says so (406) instead of answering JSON the client did not ask for.
TEST(HttpStreams, PostRoutesRefuseEventStreamsAlone) {
  TestServer s;
  auto c = s.client();
  auto r = c.Post("/api/v1/sweep", {{"Accept", "text/event-stream"}}, R"({"n":[3],"h":[0.5]})", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 406) << r->body;
  EXPECT_EQ(json::parse(r->body)["error"]["code"], "not_acceptable");
  auto both = c.Post("/api/v1/sweep", {{"Accept", "text/event-stream, application/json"}}, R"({"n":[3],"h":[0.5]})",
                     "application/json");
  ASSERT_TRUE(both);
  EXPECT_EQ(both->status, 200) << both->body;
}

TEST(HttpStreams, SweepIntegrateAndWorkPrecisionStream) {
  TestServer s;
  auto c = s.client();
  auto collect = [&](const std::string& path, const std::string& body) {
    std::vector<json> records;
    auto res = post_lines(c, path, body, "application/x-ndjson", [&](const std::string& line) {
      records.push_back(json::parse(line));
      return true;
    });
    EXPECT_TRUE(res);
    return records;
  };
  auto cells = collect("/api/v1/sweep", R"({"methods":["newton-group","fixed-point"],"n":[3,4],"h":[0.5],"differential":"exact"})");
  ASSERT_EQ(cells.size(), 5u);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(cells[k]["type"], "cell");
  EXPECT_EQ(cells.back()["type"], "result");
  EXPECT_EQ(cells.back()["cells"].size(), 4u);
  auto steps = collect("/api/v1/integrate", R"({"problem":"rigid-body","h":0.25,"t_end":1})");
  ASSERT_EQ(steps.size(), 5u);
  EXPECT_EQ(steps[0]["type"], "step");
  EXPECT_EQ(steps[0]["step"], 1);
  EXPECT_EQ(steps.back()["type"], "result");
  auto series = collect("/api/v1/work-precision",
                        R"({"problem":"rigid-body","t_end":0.5,"h":[0.1],"choices":[{"integrator":"implicit-euler"}]})");
  ASSERT_EQ(series.size(), 2u);
  EXPECT_EQ(series[0]["type"], "series");
  EXPECT_EQ(series.back()["type"], "result");
}

TEST(HttpStreams, DisconnectCancelsTheSolve) {
  std::atomic<int> last{-1};
  ServerOptions o;
  o.on_progress = [&](int i) {
    last = i;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  };
  TestServer s(o);
  auto c = s.client();
  // fixed-point with h = 50 cannot converge: it would run all 100 iterations (2 s) if not cancelled.
  int received = 0;
  post_lines(c, "/api/v1/solve", R"({"n":3,"h":50,"method":"fixed-point","max_iterations":100})", "application/x-ndjson",
             [&](const std::string&) { return ++received < 3; });  // hang up after 3 records
  EXPECT_EQ(received, 3);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (s.server->metrics().solves("cancelled") == 0 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_EQ(s.server->metrics().solves("cancelled"), 1u);
  // Stopped within a couple of iterations of the hang-up (the first write after it fails).
  EXPECT_LE(last.load(), 6);
  EXPECT_EQ(s.server->metrics().solves("max_iterations"), 0u);
  while (s.server->metrics().work_in_flight() > 0 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_EQ(s.server->metrics().streams_in_flight(), 0);
}

}  // namespace
}  // namespace lienewton::service
