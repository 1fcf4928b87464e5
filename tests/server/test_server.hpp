#pragma once
// An in-process lienewton server on an ephemeral port, a temporary web root with a file outside it (for
// traversal tests), and small client helpers (raw sockets for requests httplib::Client will not send).
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "server/http_server.hpp"
#include "server/httplib_include.hpp"

namespace lienewton::service::testing {

inline std::filesystem::path make_web_root() {
  namespace fs = std::filesystem;
  static int counter = 0;
  const fs::path base = fs::temp_directory_path() / ("lienewton-web-" + std::to_string(getpid()) + "-" + std::to_string(counter++));
  fs::create_directories(base / "web" / "sub");
  std::ofstream(base / "web" / "index.html") << "<!doctype html><title>lienewton</title>";
  std::ofstream(base / "web" / "app.js") << "export const answer = 42;\n";
  std::ofstream(base / "web" / "sub" / "index.html") << "sub";
  std::ofstream(base / "secret.txt") << "SECRET";
  std::error_code ec;
  fs::create_symlink(base / "secret.txt", base / "web" / "link.txt", ec);
  return base;
}

struct TestServer {
  explicit TestServer(ServerOptions options = {}) {
    base = make_web_root();
    options.host = "127.0.0.1";
    options.port = 0;
    options.web_root = (base / "web").string();
    options.log = &log;
    server = std::make_unique<HttpServer>(options);
    port = server->start_background();
  }
  ~TestServer() {
    server->stop();
    server.reset();
    std::error_code ec;
    std::filesystem::remove_all(base, ec);
  }
  httplib::Client client() const {
    httplib::Client c("127.0.0.1", port);
    c.set_read_timeout(30, 0);
    return c;
  }
  std::filesystem::path base;
  std::ostringstream log;  // written only by the server's workers after start; read after stop
  std::unique_ptr<HttpServer> server;
  int port = 0;
};

// Sends raw bytes and returns everything the server answers until it closes (or 5 s pass).
inline std::string raw_http(int port, const std::string& request) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<uint16_t>(port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
    ::close(fd);
    return "";
  }
  timeval tv{5, 0};
  setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  ::send(fd, request.data(), request.size(), MSG_NOSIGNAL);
  std::string out;
  char buf[4096];
  for (;;) {
    const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
    if (n <= 0) break;
    out.append(buf, static_cast<std::size_t>(n));
    // Stop at the end of the first response instead of waiting for the keep-alive timeout.
    const auto end = out.find("\r\n\r\n");
    const auto cl = out.find("Content-Length: ");
    if (end != std::string::npos && cl != std::string::npos && cl < end) {
      const std::size_t length = std::stoul(out.substr(cl + 16, out.find("\r\n", cl) - cl - 16));
      if (out.size() >= end + 4 + length) break;
    }
  }
  ::close(fd);
  return out;
}

// A fixture whose tests share one in-process server, started once per suite (a server per test would cost
// a start and a drain each).
class SharedServerTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { server_ = new TestServer(); }
  static void TearDownTestSuite() {
    delete server_;
    server_ = nullptr;
  }
  static httplib::Client client() { return server_->client(); }
  // POST a JSON body; expects `status` and returns the parsed answer, or null when there was none or it had
  // another status (a test reading a member of null then fails on a thrown type_error; reading a missing key of a
  // const object, such as an error answer's, would be undefined).
  static nlohmann::json post(const std::string& path, const std::string& body, int status = 200) {
    auto res = server_->client().Post(path, body, "application/json");
    EXPECT_TRUE(res);
    if (!res) return nlohmann::json();
    EXPECT_EQ(res->status, status) << res->body;
    if (res->status != status) return nlohmann::json();
    return nlohmann::json::parse(res->body);
  }
  // Each request (`opening`, then a case's rest) posted to `path` is a 422 naming the case's field.
  struct BadField {
    const char* rest;
    const char* field;
  };
  static void expect_422_naming(const std::string& path, const std::string& opening,
                                std::initializer_list<BadField> cases) {
    for (const BadField& c : cases) {
      const nlohmann::json e = post(path, opening + c.rest, 422);
      EXPECT_EQ(e["error"]["field"], c.field) << e.dump();
    }
  }
  static inline TestServer* server_ = nullptr;
};

// A matrix from the API's array of rows.
inline Eigen::MatrixXd matrix_from_rows(const nlohmann::json& rows) {
  Eigen::MatrixXd m(rows.size(), rows[0].size());
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (std::size_t j = 0; j < rows[i].size(); ++j) m(i, j) = rows[i][j].get<double>();
  return m;
}

inline int raw_status(const std::string& response) {
  if (response.size() < 12) return -1;
  return std::stoi(response.substr(9, 3));
}

// POSTs and feeds each complete line of the (streamed) answer to on_line; on_line returning false aborts.
inline httplib::Result post_lines(httplib::Client& client, const std::string& path, const std::string& body,
                                  const std::string& accept, const std::function<bool(const std::string&)>& on_line) {
  httplib::Request req;
  req.method = "POST";
  req.path = path;
  req.headers = {{"Accept", accept}, {"Content-Type", "application/json"}};
  req.body = body;
  auto pending = std::make_shared<std::string>();
  req.content_receiver = [pending, on_line](const char* data, size_t n, uint64_t, uint64_t) {
    pending->append(data, n);
    std::size_t nl;
    while ((nl = pending->find('\n')) != std::string::npos) {
      const std::string line = pending->substr(0, nl);
      pending->erase(0, nl + 1);
      if (!line.empty() && !on_line(line)) return false;
    }
    return true;
  };
  return client.send(req);
}

}  // namespace lienewton::service::testing
