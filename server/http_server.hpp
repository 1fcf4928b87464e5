#pragma once
// lienewton's HTTP service on cpp-httplib 0.11.4, the only code that parses HTTP, configured through its public
// API alone: one request per connection (a refused request's unread body can never be read as another
// request), per-read timeouts, a payload cap, a pre-routing handler that refuses what must not reach a handler,
// and a worker queue of its own (bounded: 503 beyond it; connections capped below the descriptor limit).
// Slow and hostile clients are for the front (deploy/nginx) to absorb.
// Routes from the route table, bounded long work (work slots per client, deadlines), NDJSON/SSE streams,
// metrics, one JSON log line per request, a drain for SIGTERM.
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
class Server;
struct Request;
}  // namespace httplib

namespace lienewton::service {

class ApiHandlers;
struct WorkerLanes;
class RequestClocks;

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
  HttpResponse respond(RouteHandler handler, const HttpRequest& req);
  // The client's address: the TCP peer, or X-Real-IP when the peer is a trusted front.
  std::string client_address(const httplib::Request& req) const;

  ServerOptions options_;
  Metrics metrics_;
  std::atomic<bool> draining_{false};
  std::atomic<bool> abort_work_{false};
  std::unique_ptr<httplib::Server> server_;
  std::shared_ptr<WorkerLanes> lanes_;
  std::unique_ptr<RequestClocks> clocks_;
  std::unique_ptr<ApiHandlers> api_;
  std::vector<std::pair<std::string, std::string>> registered_;
  std::thread thread_;
  int listen_fd_ = -1;
  int port_ = -1;
};

// The --healthcheck probe: 0 when a server at options.host:port answers /livez with 200, else 1.
int healthcheck(const ServerOptions& options);

}  // namespace lienewton::service
