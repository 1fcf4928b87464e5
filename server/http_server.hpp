#pragma once
// lienewton's HTTP service: cpp-httplib parses, routes and writes each request, but connections belong to the
// ConnectionReactor (server/connection_reactor.hpp), which hands a worker one complete request at a time.
// Routes from the route table, body/header hardening, bounded long work (work slots, deadlines, client-
// disconnect cancellation), NDJSON/SSE streams, metrics, one JSON log line per request, a drain for SIGTERM.
#include <atomic>
#include <memory>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "server/http_exchange.hpp"
#include "server/metrics.hpp"
#include "server/routes.hpp"
#include "server/server_options.hpp"

namespace httplib {
struct Request;
}  // namespace httplib

namespace lienewton::service {

class ApiHandlers;
class ConnectionReactor;
class ReactorServer;

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
  HttpResponse respond(RouteHandler handler, const httplib::Request& req);

  ServerOptions options_;
  Metrics metrics_;
  std::atomic<bool> draining_{false};
  std::atomic<bool> abort_work_{false};
  std::unique_ptr<ReactorServer> server_;
  std::unique_ptr<ConnectionReactor> reactor_;
  std::unique_ptr<ApiHandlers> api_;
  std::vector<std::pair<std::string, std::string>> registered_;
  std::thread thread_;
  int port_ = -1;
};

// The --healthcheck probe: 0 when a server at options.host:port answers /livez with 200, else 1.
int healthcheck(const ServerOptions& options);

}  // namespace lienewton::service
