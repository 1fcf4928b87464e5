// Every error status the service documents, each with a JSON body naming what was wrong.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "server/json_codec.hpp"
#include "test_server.hpp"

namespace lienewton::service {
namespace {

using testing::raw_http;
using testing::raw_status;
using testing::TestServer;

json error_of(const httplib::Result& res) {
  EXPECT_TRUE(res);
  if (!res) return {};
  EXPECT_EQ(res->get_header_value("Content-Type"), "application/json");
  return json::parse(res->body)["error"];
}

json error_of_raw(const std::string& answer) {
  const auto start = answer.find("\r\n\r\n");
  if (start == std::string::npos) return {};
  return json::parse(answer.substr(start + 4))["error"];
}

TEST(HttpErrors, ClientErrors) {
  TestServer s;
  auto c = s.client();
  auto r = c.Post("/api/v1/solve", R"({"n":3,"h":-1})", "application/json");
  EXPECT_EQ(r->status, 400);
  EXPECT_EQ(error_of(r)["field"], "h");
  EXPECT_EQ(error_of(r)["code"], "invalid_field");
  EXPECT_EQ(error_of(r)["message"], "h must be a finite number in (0, 1e6]");
  r = c.Post("/api/v1/solve", R"({"n":3,"colour":1})", "application/json");
  EXPECT_EQ(r->status, 400);
  EXPECT_EQ(error_of(r)["field"], "colour");
  r = c.Post("/api/v1/solve", R"({"n":)", "application/json");
  EXPECT_EQ(r->status, 400);
  EXPECT_EQ(error_of(r)["code"], "malformed_json");
  r = c.Post("/api/v1/solve", R"({"n":100})", "application/json");  // above --max-n (64)
  EXPECT_EQ(r->status, 400);
  EXPECT_EQ(error_of(r)["field"], "n");
  r = c.Get("/api/v1/solve/events?n=3&h=zero");
  EXPECT_EQ(r->status, 400);
  EXPECT_EQ(error_of(r)["field"], "h");
  r = c.Post("/api/v1/solve", R"({"problem":"rigid-body","n":4})", "application/json");
  EXPECT_EQ(r->status, 422);
  EXPECT_EQ(error_of(r)["code"], "unprocessable");
  EXPECT_EQ(error_of(r)["field"], "n");
  r = c.Post("/api/v1/solve", R"({"n":2,"z":[[1,1],[0,1]]})", "application/json");
  EXPECT_EQ(r->status, 422);
  EXPECT_EQ(error_of(r)["field"], "z");
  r = c.Get("/no/such/page");
  EXPECT_EQ(r->status, 404);
  EXPECT_EQ(error_of(r)["code"], "not_found");
  r = c.Post("/api/v1/nothing", "{}", "application/json");
  EXPECT_EQ(r->status, 404);
  r = c.Get("/api/v1/solve");
  EXPECT_EQ(r->status, 405);
  EXPECT_EQ(r->get_header_value("Allow"), "POST");
  EXPECT_EQ(error_of(r)["code"], "method_not_allowed");
  r = c.Post("/metrics", "{}", "application/json");
  EXPECT_EQ(r->status, 405);
  r = c.Post("/api/v1/solve", "<n>3</n>", "application/xml");
  EXPECT_EQ(r->status, 415);
  EXPECT_EQ(error_of(r)["code"], "unsupported_media_type");
}

TEST(HttpErrors, BodyRulesBeforeTheBodyIsRead) {
  ServerOptions o;
  o.max_body = 1000;
  // A body announced beyond the cap is skipped by cpp-httplib until the client stops sending, which it notices by
  // its read timeout: well inside raw_http's 5 s wait, so that the answer is not a race between the two.
  o.read_timeout = 1;
  TestServer s(o);
  // No Content-Length.
  std::string answer = raw_http(s.port, "POST /api/v1/solve HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\n\r\n");
  EXPECT_EQ(raw_status(answer), 411) << answer;
  EXPECT_EQ(error_of_raw(answer)["code"], "length_required");
  // Chunked body: refused before cpp-httplib reads it (it would bypass the size cap).
  answer = raw_http(s.port, "POST /api/v1/solve HTTP/1.1\r\nHost: x\r\nTransfer-Encoding: chunked\r\n\r\n5\r\n{\"n\":\r\n0\r\n\r\n");
  EXPECT_EQ(raw_status(answer), 411) << answer;
  EXPECT_NE(answer.find("Connection: close"), std::string::npos);
  // A body on GET or HEAD that carries a request of its own: one answer, the inner request never runs.
  for (const char* method : {"GET", "HEAD"}) {
    const std::string inner = "GET /metrics HTTP/1.1\r\nHost: x\r\n\r\n";
    answer = raw_http(s.port, std::string(method) + " /livez HTTP/1.1\r\nHost: x\r\nContent-Length: " +
                                  std::to_string(inner.size()) + "\r\n\r\n" + inner);
    EXPECT_EQ(raw_status(answer), 400) << answer;
    EXPECT_EQ(answer.find("HTTP/1.1 ", 1), std::string::npos) << answer;
  }
  // A bare CR or NUL in a header value, and "Connection: CLOSE" in any case.
  answer = raw_http(s.port, std::string("GET /livez HTTP/1.1\r\nHost: x\r\nX-A: a\rb\r\n\r\n"));
  EXPECT_EQ(raw_status(answer), 400) << answer;
  answer = raw_http(s.port, std::string("GET /livez HTTP/1.1\r\nHost: x\r\nX-A: a\0b\r\n\r\n", 42));
  EXPECT_EQ(raw_status(answer), 400) << answer;
  // An encoded newline is refused where it would be a header's own (httplib decodes it), but not in Referer: the
  // dashboard's address keeps a program g, newlines and all, in its query.
  answer = raw_http(s.port, "GET /livez HTTP/1.1\r\nHost: x\r\nX-A: a%0d%0aX-B: c\r\n\r\n");
  EXPECT_EQ(raw_status(answer), 400) << answer;
  answer = raw_http(s.port, "GET /livez HTTP/1.1\r\nHost: x\r\nReferer: http://x/?g=a%3D1%3B%0Ag%3Da\r\n\r\n");
  EXPECT_EQ(raw_status(answer), 200) << answer;
  answer = raw_http(s.port, "GET /livez HTTP/1.1\r\nHost: x\r\nConnection: CLOSE\r\n\r\n");
  EXPECT_EQ(raw_status(answer), 200) << answer;
  EXPECT_NE(answer.find("Connection: close"), std::string::npos) << answer;
  // Compressed body.
  answer = raw_http(s.port, "POST /api/v1/solve HTTP/1.1\r\nHost: x\r\nContent-Encoding: gzip\r\nContent-Length: 4\r\n\r\nabcd");
  EXPECT_EQ(raw_status(answer), 415) << answer;
  // Too large, announced: refused without reading, and the unread body is not parsed as a request.
  answer = raw_http(s.port, "POST /api/v1/solve HTTP/1.1\r\nHost: x\r\nContent-Length: 5000\r\n\r\nGET /livez HTTP/1.1\r\n\r\n");
  EXPECT_EQ(raw_status(answer), 413) << answer;
  EXPECT_EQ(answer.find("HTTP/1.1 200"), std::string::npos) << answer;
  // Not HTTP at all: the parser's 400 still gets a JSON body.
  answer = raw_http(s.port, "HELLO\r\n\r\n");
  EXPECT_EQ(raw_status(answer), 400) << answer;
  EXPECT_EQ(error_of_raw(answer)["code"], "bad_request");
}

// The clients here are named by X-Real-IP from a trusted front (the test's loopback peer).
httplib::Result solve_as(const TestServer& s, const std::string& client) {
  auto c = s.client();
  return c.Post("/api/v1/solve", {{"X-Real-IP", client}}, R"({"n":3,"h":0.5})", "application/json");
}

// A progress hook that holds every solve inside its work slot until release().
struct HeldWork {
  std::mutex m;
  std::condition_variable cv;
  bool released = false;
  std::atomic<int> held{0};

  std::function<void(int)> hook() {
    return [this](int) {
      ++held;
      std::unique_lock lock(m);
      cv.wait(lock, [this] { return released; });
    };
  }
  void wait_for(int count) const {
    while (held.load() < count) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  void release() {
    {
      std::lock_guard lock(m);
      released = true;
    }
    cv.notify_all();
  }
  // threads - 2 work slots, half of them per client address; trusted: the loopback peer is a front.
  ServerOptions options(int threads, bool trusted) {
    ServerOptions o;
    o.threads = threads;
    if (trusted) o.trusted_fronts = {"127.0.0.1"};
    o.on_progress = hook();
    return o;
  }
};

TEST(HttpErrors, OverCapacityKeepsLivezAnswering) {
  HeldWork work;
  TestServer s(work.options(6, true));  // four work slots, two per client address
  std::vector<std::thread> holders;
  for (const char* client : {"10.0.0.1", "10.0.0.1", "10.0.0.2", "10.0.0.2"}) {
    holders.emplace_back([&s, client] { solve_as(s, client); });
  }
  work.wait_for(4);
  auto r = solve_as(s, "10.0.0.3");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 503);
  EXPECT_EQ(error_of(r)["code"], "over_capacity");
  EXPECT_EQ(r->get_header_value("Retry-After"), "1");
  auto c = s.client();
  auto live = c.Get("/livez");
  ASSERT_TRUE(live);
  EXPECT_EQ(live->status, 200);
  work.release();
  for (auto& t : holders) t.join();
}

TEST(HttpErrors, OneClientAddressTakesAtMostHalfTheWorkSlots) {
  HeldWork work;
  TestServer s(work.options(6, true));  // four work slots, two per client address
  std::vector<std::thread> holders;
  for (int k = 0; k < 2; ++k) holders.emplace_back([&s] { solve_as(s, "10.0.0.1"); });
  work.wait_for(2);
  auto same = solve_as(s, "10.0.0.1");
  ASSERT_TRUE(same) << httplib::to_string(same.error());
  EXPECT_EQ(same->status, 429) << same->body;
  EXPECT_EQ(error_of(same)["code"], "client_over_capacity");
  work.release();
  for (auto& t : holders) t.join();
  // Another address still gets a slot (the hook no longer holds).
  auto other = solve_as(s, "10.0.0.2");
  ASSERT_TRUE(other) << httplib::to_string(other.error());
  EXPECT_EQ(other->status, 200) << other->body;
}

TEST(HttpErrors, XRealIpIsBelievedOnlyFromATrustedFront) {
  HeldWork work;
  // Two work slots, one per client address; no trusted front: every request is from 127.0.0.1, whatever
  // X-Real-IP says.
  TestServer s(work.options(4, false));
  std::thread holder([&s] { solve_as(s, "10.0.0.1"); });
  work.wait_for(1);
  auto forged = solve_as(s, "10.0.0.2");
  ASSERT_TRUE(forged);
  EXPECT_EQ(forged->status, 429);
  work.release();
  holder.join();
}

TEST(HttpErrors, DeadlineGives504AndCancelsTheSolve) {
  ServerOptions o;
  o.request_timeout = 0.2;
  std::atomic<int> last{0};
  o.on_progress = [&](int i) {
    last = i;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  };
  TestServer s(o);
  auto c = s.client();
  // Fixed point with a large h does not converge: without the deadline it would run all 1000 iterations.
  auto r = c.Post("/api/v1/solve", R"({"n":3,"h":50,"method":"fixed-point","max_iterations":1000})", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 504);
  EXPECT_EQ(error_of(r)["code"], "deadline_exceeded");
  EXPECT_LT(last.load(), 50);
  // Streamed, the deadline ends the stream with an error record.
  std::vector<json> records;
  auto streamed = testing::post_lines(c, "/api/v1/solve", R"({"n":3,"h":50,"method":"fixed-point","max_iterations":1000})",
                                      "application/x-ndjson", [&](const std::string& line) {
                                        records.push_back(json::parse(line));
                                        return true;
                                      });
  ASSERT_TRUE(streamed);
  ASSERT_FALSE(records.empty());
  EXPECT_EQ(records.back()["type"], "error");
  EXPECT_EQ(records.back()["error"]["code"], "deadline_exceeded");
  EXPECT_EQ(s.server->metrics().solves("cancelled"), 2u);
}

// A sweep has a budget of its own (--sweep-timeout): a map that outlasts the single-solve deadline finishes,
// and one that outlasts its own budget says how many cells it finished and how many were never computed.
TEST(HttpErrors, SweepsRunOnTheirOwnBudgetAndCountWhatTheyDid) {
  constexpr const char* kSweep = R"({"methods":["newton-group"],"differential":"exact","n":[3,4],"h":[0.25,0.5,1]})";
  ServerOptions o;
  o.request_timeout = 0.05;
  o.sweep_timeout = 60;
  o.on_progress = [](int) { std::this_thread::sleep_for(std::chrono::milliseconds(20)); };  // 6 cells: 0.12 s
  {
    TestServer s(o);
    auto c = s.client();
    auto r = c.Post("/api/v1/sweep", kSweep, "application/json");
    ASSERT_TRUE(r);
    ASSERT_EQ(r->status, 200) << r->body;
    EXPECT_EQ(json::parse(r->body)["cells"].size(), 6u);
  }
  o.sweep_timeout = 0.05;
  TestServer s(o);
  auto c = s.client();
  auto r = c.Post("/api/v1/sweep", kSweep, "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 504);
  const std::string message = error_of(r)["message"];
  EXPECT_NE(message.find("limit of 0.05 s"), std::string::npos) << message;
  EXPECT_NE(message.find(" of 6 cells finished, "), std::string::npos) << message;
  EXPECT_NE(message.find(" not computed"), std::string::npos) << message;
}

}  // namespace
}  // namespace lienewton::service
