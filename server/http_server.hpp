#pragma once
// lienewton's HTTP service on cpp-httplib: routes from the route table, body/header hardening before any body
// is read, bounded long work (work slots, deadlines, client-disconnect cancellation), NDJSON/SSE streams,
// metrics, one JSON log line per request, and a drain for SIGTERM.
#include <atomic>
#include <memory>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "server/metrics.hpp"
#include "server/server_options.hpp"

namespace httplib { class Server; }

namespace lienewton::service {

class ApiHandlers;

class HttpServer {
 public:
  explicit HttpServer(ServerOptions options);
  ~HttpServer();
  HttpServer(const HttpServer&) = delete;
  HttpServer& operator=(const HttpServer&) = delete;

  // Binds host:port (port 0: any free port) and returns the port; throws std::runtime_error on failure.
  int bind();
  // Serves until stop(); blocks. bind() first.
  void listen();
  // bind() + listen() on a background thread; returns once the server accepts connections.
  int start_background();

  // SIGTERM: /readyz turns 503 and new work is refused; open work gets shutdown_grace seconds to finish, then
  // is cancelled (streams end with an error record); then the listener stops. Returns within `limit` seconds.
  void drain_and_stop(double limit_seconds = 9.0);
  void stop();

  bool draining() const { return draining_.load(); }
  int port() const { return port_; }
  const Metrics& metrics() const { return metrics_; }
  // (method, path) of every handler registered from the route table.
  const std::vector<std::pair<std::string, std::string>>& registered_routes() const { return registered_; }

 private:
  void install();

  ServerOptions options_;
  std::string web_root_;
  Metrics metrics_;
  std::atomic<bool> draining_{false};
  std::atomic<bool> abort_work_{false};
  std::unique_ptr<httplib::Server> server_;
  std::unique_ptr<ApiHandlers> api_;
  std::vector<std::pair<std::string, std::string>> registered_;
  std::thread thread_;
  int port_ = -1;
};

}  // namespace lienewton::service
