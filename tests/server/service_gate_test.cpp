// The gate before long work: a request takes its work slot, the per-client limit and its cancellation token
// before its user's program is compiled or evaluated; the program is compiled and the seeded start drawn once per
// request and n, and the request validated once; and every route, plain or streamed, stops soon after its client
// has gone.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <ostream>
#include <thread>

#include "core/problem_spec.hpp"
#include "core/program_cache.hpp"
#include "core/spec_cache.hpp"
#include "server/json_codec.hpp"
#include "test_server.hpp"

namespace lienewton::service {
namespace {

using Clock = std::chrono::steady_clock;
using testing::TestServer;

const std::string kSine = R"("g":"u = sin(y)*(2*y - 5*y^2); g = u - u'")";

json error_of(const httplib::Result& r) { return json::parse(r->body)["error"]; }

// What the server did for one request: programs compiled, seeded starts drawn, problems validated.
struct Work {
  std::uint64_t compilations = 0, seeded_starts = 0, validations = 0;
  bool operator==(const Work&) const = default;
};
std::ostream& operator<<(std::ostream& os, const Work& w) {
  return os << "{compilations " << w.compilations << ", seeded starts " << w.seeded_starts << ", validations "
            << w.validations << "}";
}

// POSTs `body` and returns how far the process-wide counters moved while the server answered it.
Work work_of(TestServer& s, const std::string& path, const std::string& body) {
  const Work before{ProgramCache::compilations(), SpecCache::seeded_starts(), problem_validations()};
  auto r = s.client().Post(path, body, "application/json");
  EXPECT_TRUE(r);
  if (r) {
    EXPECT_EQ(r->status, 200) << path << ": " << r->body;
  }
  return {ProgramCache::compilations() - before.compilations, SpecCache::seeded_starts() - before.seeded_starts,
          problem_validations() - before.validations};
}

// A request is resolved once: the handler validates it before a stream's status line and the core runs it without
// checking it again; its program is compiled and its seeded start drawn once per n, however often validation, the
// run and the output checks read them.
TEST(ServiceGate, ARequestIsResolvedOncePerN) {
  TestServer s;
  EXPECT_EQ(work_of(s, "/api/v1/solve", "{" + kSine + R"(,"n":3,"h":0.5})"), (Work{1, 1, 1}));
  EXPECT_EQ(work_of(s, "/api/v1/solve", R"({"n":3,"h":0.5,"include_iterates":true})"), (Work{0, 1, 1}));
  // A given z is the start: nothing is drawn.
  EXPECT_EQ(work_of(s, "/api/v1/solve", R"({"n":3,"h":0.5,"z":[[1,0,0],[0,1,0],[0,0,1]]})"), (Work{0, 0, 1}));
  EXPECT_EQ(work_of(s, "/api/v1/sweep", "{" + kSine + R"(,"methods":["newton-group","fixed-point"],)"
                                                      R"("n":[3,4,5],"h":[0.25,0.5,1]})"),
            (Work{3, 3, 3}));
  EXPECT_EQ(work_of(s, "/api/v1/basins", "{" + kSine + R"(,"n":3,"h":1,"size":6})"), (Work{1, 1, 1}));
  EXPECT_EQ(work_of(s, "/api/v1/integrate", "{" + kSine + R"(,"n":3,"h":0.1,"t_end":0.5})"), (Work{1, 1, 1}));
  // Without h: the codec validates the problem to read the default step off its field at the start (by the same
  // compiled program and start), and the handler validates the whole request.
  EXPECT_EQ(work_of(s, "/api/v1/integrate", "{" + kSine + R"(,"n":3,"t_end":0.5})"), (Work{1, 1, 2}));
  EXPECT_EQ(work_of(s, "/api/v1/render/heatmap", "{" + kSine + R"(,"n":[3,4],"h":[0.5,1]})"), (Work{2, 2, 2}));
}

TEST(ServiceGate, ARepeatedNOrHIsRefusedNamingItsList) {
  TestServer s;
  auto c = s.client();
  auto n = c.Post("/api/v1/sweep", "{" + kSine + R"(,"n":[3,4,3],"h":[0.5]})", "application/json");
  ASSERT_TRUE(n);
  EXPECT_EQ(n->status, 422);
  EXPECT_EQ(error_of(n)["field"], "n");
  auto h = c.Post("/api/v1/sweep", R"({"n":[3],"h":[0.5,1,0.5]})", "application/json");
  ASSERT_TRUE(h);
  EXPECT_EQ(h->status, 422);
  EXPECT_EQ(error_of(h)["field"], "h");
  // A stream's refusal is still a plain answer: validation runs before its status line.
  httplib::Headers accept{{"Accept", "application/x-ndjson"}};
  auto streamed = c.Post("/api/v1/sweep", accept, R"({"n":[3,3],"h":[0.5]})", "application/json");
  ASSERT_TRUE(streamed);
  EXPECT_EQ(streamed->status, 422);
  EXPECT_EQ(error_of(streamed)["field"], "n");
}

// Work slots held by a hook until released.
struct Held {
  std::mutex m;
  std::condition_variable cv;
  bool released = false;
  std::atomic<int> held{0};
  void hold() {
    ++held;
    std::unique_lock lock(m);
    cv.wait(lock, [this] { return released; });
  }
  void release() {
    {
      std::lock_guard lock(m);
      released = true;
    }
    cv.notify_all();
  }
};

TEST(ServiceGate, AClientBeyondItsLimitIsRefusedBeforeItsProgramIsCompiled) {
  Held work;
  ServerOptions o;
  o.threads = 4;  // two work slots, one per client address
  o.on_progress = [&](int) { work.hold(); };
  TestServer s(o);
  std::thread holder([&] { s.client().Post("/api/v1/solve", R"({"n":3,"h":0.5})", "application/json"); });
  while (work.held.load() < 1) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  const std::uint64_t before = ProgramCache::compilations();
  auto r = s.client().Post("/api/v1/sweep", "{" + kSine + R"(,"n":[3,4,5,6],"h":[0.5]})", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 429);
  EXPECT_EQ(ProgramCache::compilations(), before);
  work.release();
  holder.join();
}

// A raw client that sends `body` to `path`, waits `seconds` and closes without reading the answer.
void abandon(int port, const std::string& path, const std::string& body, double seconds) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<uint16_t>(port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  const std::string request = "POST " + path + " HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json\r\n"
                              "Content-Length: " + std::to_string(body.size()) + "\r\n\r\n" + body;
  ::send(fd, request.data(), request.size(), MSG_NOSIGNAL);
  std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
  ::close(fd);
}

// A plain (non-streamed) answer writes nothing until its work ends, yet the work stops within about one
// iteration of the client's leaving, and the reason is counted as client_gone.
void expect_stops_when_abandoned(const std::string& path, const std::string& body) {
  std::atomic<Clock::rep> last{0};
  ServerOptions o;
  o.sweep_timeout = o.request_timeout = 60;
  o.on_progress = [&](int) {
    last = Clock::now().time_since_epoch().count();
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  };
  TestServer s(o);
  abandon(s.port, path, body, 1.0);
  const auto left = Clock::now();
  const auto deadline = left + std::chrono::seconds(5);
  while (s.server->metrics().work_in_flight() > 0 && Clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_EQ(s.server->metrics().work_in_flight(), 0) << path;
  const auto stopped = Clock::time_point(Clock::duration(last.load()));
  EXPECT_GT(last.load(), 0) << path << " never made progress";
  EXPECT_LT(std::chrono::duration<double>(stopped - left).count(), 0.3) << path;
  EXPECT_LT(std::chrono::duration<double>(Clock::now() - left).count(), 1.0) << path;
}

TEST(ServiceGate, PlainRoutesStopWhenTheirClientLeaves) {
  // Each would run for minutes (20 ms per cell, row, step or iteration) if nothing noticed.
  expect_stops_when_abandoned("/api/v1/sweep", R"({"methods":["newton-group","fixed-point"],"n":[3,4,5,6,7,8],)"
                                               R"("h":[0.125,0.25,0.5,1,2,4,8,16,32,64]})");
  expect_stops_when_abandoned("/api/v1/solve", R"({"n":3,"h":50,"method":"fixed-point","max_iterations":10000})");
  expect_stops_when_abandoned("/api/v1/render/heatmap", R"({"methods":["newton-group","fixed-point"],)"
                                                        R"("n":[3,4,5,6,7,8],"h":[0.125,0.25,0.5,1,2,4,8,16,32,64]})");
}

TEST(ServiceGate, AHeatmapWhoseEveryCellPassesTheDeadlineIs504) {
  ServerOptions o;
  o.sweep_timeout = 0.05;
  // The first cell's only callback comes after the deadline: no cell finishes in time.
  o.on_progress = [](int) { std::this_thread::sleep_for(std::chrono::milliseconds(100)); };
  TestServer s(o);
  auto r = s.client().Post("/api/v1/render/heatmap",
                           R"({"methods":["fixed-point"],"n":[40],"h":[50],"max_iterations":10000})", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 504) << r->body;
  EXPECT_EQ(error_of(r)["code"], "deadline_exceeded");
}

}  // namespace
}  // namespace lienewton::service
