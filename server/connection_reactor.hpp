#pragma once
// The connection reactor: one epoll thread owns every client socket while it is idle or still sending its
// request, so slow, dripping and idle clients cost a file descriptor, not a worker. A request reaches a worker
// only when its head and its whole body (Content-Length) are in memory; the worker gets exactly those bytes,
// so an unread or refused body can never be parsed as the next request (no smuggling), and pipelined requests
// are served one after another in order. The reactor itself answers, and closes:
//   408 when a request's head and body take longer than limits.request_read_timeout from its first byte,
//   431 beyond max_header_bytes / max_headers, 411 for Transfer-Encoding, 400 for a bad Content-Length,
//   413 beyond max_body (without "100 Continue"); 503 for a connection beyond max_connections in total or per
//   client address, unless its one request is /livez or /readyz (so probes answer under a connection flood),
//   and at once beyond max_connections + 64.
// While a worker serves a request the socket is watched for EPOLLRDHUP: a client that leaves sets the
// request's client_gone flag, which cancels its work. Health routes have their own workers.
// Transport only: it knows HTTP/1.1 framing, not cpp-httplib and not the handlers.
#include <atomic>
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <string_view>

namespace lienewton::service {

struct ReactorLimits {
  std::size_t max_header_bytes = 16384;  // request line + headers
  std::size_t max_headers = 100;
  std::size_t max_body = 1 << 20;
  double request_read_timeout = 10;      // seconds from a request's first byte to its last
  double keep_alive_timeout = 2;         // seconds a connection may idle between requests
  int max_connections = 512;
  int max_connections_per_client = 64;
  int workers = 8;                       // serve complete requests
  int health_workers = 2;                // serve only health routes, so they answer under any load
};

// One complete request, head and body, as a worker gets it.
struct ConnectionRequest {
  int fd = -1;
  std::string remote_ip;
  int remote_port = 0;
  std::string local_ip;
  int local_port = 0;
  std::string bytes;  // the head (Expect and, on API routes, Range removed) and the body
  std::shared_ptr<const std::atomic<bool>> client_gone;
};

class ConnectionReactor {
 public:
  // Serves one request on a worker (writes its answer to request.fd); returns true to keep the connection.
  using Serve = std::function<bool(const ConnectionRequest& request)>;
  // Called for each request the reactor refuses itself, with status and error code.
  using OnRefusal = std::function<void(int status, std::string_view code)>;
  struct Routing {
    std::function<bool(std::string_view path)> is_health;   // served by the health workers
    std::function<bool(std::string_view path)> ignores_range;  // Range removed before serving
  };

  ConnectionReactor(ReactorLimits limits, Routing routing, Serve serve, OnRefusal on_refusal);
  ~ConnectionReactor();
  ConnectionReactor(const ConnectionReactor&) = delete;
  ConnectionReactor& operator=(const ConnectionReactor&) = delete;

  // Takes ownership of a freshly accepted socket.
  void adopt(int fd);
  // Closes every connection not being served, lets the workers finish, then joins all threads.
  void stop();
  int open_connections() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lienewton::service
