// SIGTERM drain of the real binary: /readyz turns 503, an open stream ends with a terminal record, and the
// process exits 0 within 10 s.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>

#include "server/json_codec.hpp"
#include "test_server.hpp"

namespace lienewton::service {
namespace {

using Clock = std::chrono::steady_clock;

struct Child {
  pid_t pid = -1;
  int out = -1;
};

Child spawn_server() {
  int fds[2];
  if (pipe(fds) != 0) return {};
  const pid_t pid = fork();
  if (pid == 0) {
    dup2(fds[1], STDOUT_FILENO);
    close(fds[0]);
    close(fds[1]);
    execl(LIENEWTON_SERVER_BINARY, LIENEWTON_SERVER_BINARY, "--port", "0", "--shutdown-grace", "0.5", "--web-root",
          LIENEWTON_SOURCE_DIR "/web", static_cast<char*>(nullptr));
    _exit(127);
  }
  close(fds[1]);
  return {pid, fds[0]};
}

TEST(Shutdown, SigtermDrainsStreamsAndExitsZero) {
  Child child = spawn_server();
  ASSERT_GT(child.pid, 0);
  // The first stdout line announces the port; later lines (request logs) are drained so the pipe never fills.
  std::mutex m;
  std::string output;
  std::thread reader([&] {
    char buf[4096];
    ssize_t n;
    while ((n = read(child.out, buf, sizeof buf)) > 0) {
      std::lock_guard lock(m);
      output.append(buf, static_cast<std::size_t>(n));
    }
  });
  int port = 0;
  for (auto until = Clock::now() + std::chrono::seconds(10); port == 0 && Clock::now() < until;) {
    {
      std::lock_guard lock(m);
      if (auto nl = output.find('\n'); nl != std::string::npos) port = json::parse(output.substr(0, nl))["port"].get<int>();
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_GT(port, 0) << output;

  // The paper's full default sweep takes far longer than the grace period.
  std::atomic<int> cells{0};
  std::vector<json> records;
  std::thread stream([&] {
    httplib::Client c("127.0.0.1", port);
    c.set_read_timeout(20, 0);
    testing::post_lines(c, "/api/v1/sweep", R"({"problem":"paper-sine","differential":"finite-difference"})",
                        "application/x-ndjson", [&](const std::string& line) {
                          records.push_back(json::parse(line));
                          ++cells;
                          return true;
                        });
  });
  for (auto until = Clock::now() + std::chrono::seconds(10); cells.load() == 0 && Clock::now() < until;) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_GT(cells.load(), 0);

  const auto sent = Clock::now();
  ASSERT_EQ(kill(child.pid, SIGTERM), 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  {
    httplib::Client c("127.0.0.1", port);
    auto ready = c.Get("/readyz");
    ASSERT_TRUE(ready);
    EXPECT_EQ(ready->status, 503);
    auto refused = c.Post("/api/v1/solve", R"({"n":3})", "application/json");
    ASSERT_TRUE(refused);
    EXPECT_EQ(refused->status, 503);
  }
  int status = 0;
  pid_t done = 0;
  while ((done = waitpid(child.pid, &status, WNOHANG)) == 0 && Clock::now() - sent < std::chrono::seconds(10)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - sent).count();
  if (done == 0) {
    kill(child.pid, SIGKILL);
    waitpid(child.pid, &status, 0);
  }
  stream.join();
  reader.join();
  close(child.out);
  ASSERT_EQ(done, child.pid) << "still running after " << seconds << " s";
  EXPECT_LT(seconds, 10.0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  ASSERT_FALSE(records.empty());
  EXPECT_EQ(records.back()["type"], "error");
  EXPECT_EQ(records.back()["error"]["code"], "shutting_down");
  EXPECT_NE(output.find("\"event\":\"stopped\""), std::string::npos);
}

}  // namespace
}  // namespace lienewton::service
