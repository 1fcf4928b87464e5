// The handlers without any transport: an HttpRequest value in, an HttpResponse (or its body stream) out.
#include "server/api_handlers.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <sstream>
#include <string>
#include <vector>


namespace lienewton::service {
namespace {

struct Handlers {
  ServerOptions options;
  Metrics metrics;
  std::atomic<bool> draining{false};
  std::atomic<bool> abort_work{false};
  ApiHandlers api{options, metrics, draining, abort_work};
};

const char* kSolve = R"({"problem":"paper-linear","n":4,"h":0.5,"method":"newton-group","differential":"exact"})";

HttpRequest post(const char* path, std::string body, std::string accept = "application/json") {
  HttpRequest req;
  req.method = "POST";
  req.path = path;
  req.headers.emplace("accept", std::move(accept));  // any case: header names compare case-insensitively
  req.body = std::move(body);
  return req;
}

std::vector<json> ndjson_lines(const std::string& text) {
  std::vector<json> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(json::parse(line));
  return lines;
}

TEST(ApiHandlers, ReadinessFollowsTheDrainFlag) {
  Handlers h;
  EXPECT_EQ(h.api.readyz({}).status, 200);
  h.draining = true;
  const HttpResponse res = h.api.readyz({});
  EXPECT_EQ(res.status, 503);
  EXPECT_EQ(json::parse(res.body)["status"], "draining");
}

// The plain JSON answer and the stream's closing record are the same result (wall times aside).
TEST(ApiHandlers, JsonAnswerEqualsTheStreamsResult) {
  Handlers h;
  const HttpResponse plain = h.api.command(post("/api/v1/solve", kSolve));
  ASSERT_EQ(plain.status, 200);
  EXPECT_FALSE(plain.stream);
  EXPECT_EQ(plain.content_type, "application/json");
  EXPECT_EQ(h.metrics.work_in_flight(), 0);
  HttpResponse streamed = h.api.command(post("/api/v1/solve", kSolve, "application/x-ndjson"));
  std::string body;
  ASSERT_TRUE(streamed.stream([&](std::string_view chunk) { return body.append(chunk), true; }));
  json last = ndjson_lines(body).back();
  json expected = json::parse(plain.body);
  for (json* j : {&last, &expected}) {  // timings differ from run to run
    for (const char* timing : {"seconds", "cpu_seconds"}) {
      j->erase(timing);
      for (auto& record : (*j)["trace"]) record.erase(timing);
    }
  }
  last.erase("type");
  EXPECT_EQ(last, expected);
}

TEST(ApiHandlers, NdjsonStreamsOneRecordPerIterateThenTheResult) {
  Handlers h;
  HttpResponse res = h.api.command(post("/api/v1/solve", kSolve, "application/x-ndjson"));
  ASSERT_TRUE(res.stream);
  EXPECT_EQ(res.content_type, "application/x-ndjson");
  EXPECT_EQ(h.metrics.work_in_flight(), 1);  // the stream holds the work slot until it is dropped
  std::string body;
  EXPECT_TRUE(res.stream([&](std::string_view chunk) { return body.append(chunk), true; }));
  const auto lines = ndjson_lines(body);
  ASSERT_GE(lines.size(), 2u);
  const json& result = lines.back();
  EXPECT_EQ(result["type"], "result");
  EXPECT_EQ(lines.size() - 1, result["iterations"].get<std::size_t>() + 1);  // iterates 0..n, then the result
  for (std::size_t i = 0; i + 1 < lines.size(); ++i) EXPECT_EQ(lines[i]["type"], "iteration") << i;
  res = HttpResponse{};
  EXPECT_EQ(h.metrics.work_in_flight(), 0);
}

// The GET form reads its request from query parameters and always streams Server-Sent Events.
TEST(ApiHandlers, SolveEventsStreamsSseFromQueryParameters) {
  Handlers h;
  HttpRequest req;
  req.method = "GET";
  req.path = "/api/v1/solve/events";
  req.params = {{"problem", "paper-linear"}, {"n", "3"}, {"h", "0.5"}, {"method", "newton-algebra"}};
  HttpResponse res = h.api.solve_events(req);
  ASSERT_TRUE(res.stream);
  EXPECT_EQ(res.content_type, "text/event-stream");
  std::vector<std::string> events;
  ASSERT_TRUE(res.stream([&](std::string_view chunk) { return events.emplace_back(chunk), true; }));
  ASSERT_GE(events.size(), 2u);
  EXPECT_EQ(events.front().rfind("event: iteration\ndata: {\"type\":\"iteration\"", 0), 0u) << events.front();
  EXPECT_EQ(events.back().rfind("event: result\ndata: {\"type\":\"result\"", 0), 0u) << events.back();
  EXPECT_EQ(events.back().substr(events.back().size() - 2), "\n\n");
}

TEST(ApiHandlers, AStreamStopsWhenTheClientIsGone) {
  Handlers h;
  HttpResponse res = h.api.command(post("/api/v1/solve", kSolve, "application/x-ndjson"));
  ASSERT_TRUE(res.stream);
  int writes = 0;
  EXPECT_FALSE(res.stream([&](std::string_view) { return ++writes, false; }));
  EXPECT_EQ(writes, 1);  // the first failed write cancels the solve; no result record is attempted
  res = HttpResponse{};
  EXPECT_EQ(h.metrics.work_in_flight(), 0);
}

}  // namespace
}  // namespace lienewton::service
