#include "server/http_server.hpp"

#include "server/httplib_include.hpp"

#include <poll.h>
#include <sys/socket.h>

#include <chrono>
#include <cstring>
#include <ctime>
#include <regex>
#include <stdexcept>

#include "server/api_handlers.hpp"
#include "server/connection_reactor.hpp"
#include "server/http_errors.hpp"
#include "server/request_limits.hpp"
#include "server/routes.hpp"
#include "core/request_error.hpp"

namespace lienewton::service {
namespace {

using Clock = std::chrono::steady_clock;

// What pre-routing learned about the request, for the logger and metrics. cpp-httplib runs pre-routing,
// the handler and the logger of one request on the same worker thread.
struct RequestContext {
  bool active = false;
  Clock::time_point start;
  std::string id;
  std::string route;
};
thread_local RequestContext t_context;
// The connection request the worker thread is serving (set around process_request), and whether the
// connection must close after this answer (a refused request).
thread_local const ConnectionRequest* t_connection = nullptr;
thread_local bool t_close_after = false;
// Whether pre-routing saw the request; a request cpp-httplib could not parse (400, 414) ends its connection.
thread_local bool t_routed = false;

// The methods metrics may name; anything else is counted as "other" (label values from a fixed set).
std::string method_label(const std::string& method) {
  static const char* const kKnown[] = {"GET", "HEAD", "POST", "PUT", "DELETE", "OPTIONS", "PATCH", "CONNECT", "TRACE"};
  for (const char* m : kKnown) {
    if (method == m) return method;
  }
  return method.empty() ? "-" : "other";
}

// cpp-httplib's accept loop hands each socket to the task queue; this one runs the hand-over (to the
// reactor) on the accept thread itself.
class InlineTaskQueue : public httplib::TaskQueue {
 public:
  void enqueue(std::function<void()> fn) override { fn(); }
  void shutdown() override {}
};

// cpp-httplib's view of one complete request: reads come from the bytes the reactor collected (and end there,
// so nothing past this request can be read), writes go to the socket. Writes shorter than kCoalesce bytes
// (status line, header lines) are gathered and sent with the next larger write or at the end.
class RequestStream : public httplib::Stream {
 public:
  static constexpr std::size_t kCoalesce = 64;
  RequestStream(const ConnectionRequest& request, int write_timeout_ms)
      : request_(request), write_timeout_ms_(write_timeout_ms) {}

  bool is_readable() const override { return read_pos_ < request_.bytes.size(); }
  bool is_writable() const override { return !failed_ && !request_.client_gone->load() && wait_writable(); }
  ssize_t read(char* ptr, std::size_t size) override {
    const std::size_t n = std::min(size, request_.bytes.size() - read_pos_);
    std::memcpy(ptr, request_.bytes.data() + read_pos_, n);
    read_pos_ += n;
    return static_cast<ssize_t>(n);
  }
  ssize_t write(const char* ptr, std::size_t size) override {
    pending_.append(ptr, size);
    if (size < kCoalesce) return static_cast<ssize_t>(size);
    return flush() ? static_cast<ssize_t>(size) : -1;
  }
  void get_remote_ip_and_port(std::string& ip, int& port) const override {
    ip = request_.remote_ip;
    port = request_.remote_port;
  }
  void get_local_ip_and_port(std::string& ip, int& port) const override {
    ip = request_.local_ip;
    port = request_.local_port;
  }
  socket_t socket() const override { return request_.fd; }

  // Sends what is gathered; false when the client is gone or stopped reading for write_timeout.
  bool flush() {
    std::string_view rest = pending_;
    while (!rest.empty() && !failed_) {
      const ssize_t n = ::send(request_.fd, rest.data(), rest.size(), MSG_NOSIGNAL);
      if (n > 0) {
        rest.remove_prefix(static_cast<std::size_t>(n));
      } else if (n < 0 && errno == EINTR) {
        continue;
      } else if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK) && wait_writable()) {
        continue;
      } else {
        failed_ = true;
      }
    }
    pending_.clear();
    return !failed_;
  }

 private:
  bool wait_writable() const {
    pollfd p{request_.fd, POLLOUT, 0};
    return ::poll(&p, 1, write_timeout_ms_) == 1 && !(p.revents & (POLLERR | POLLHUP));
  }
  const ConnectionRequest& request_;
  int write_timeout_ms_;
  std::size_t read_pos_ = 0;
  std::string pending_;
  bool failed_ = false;
};

std::string regex_escape(const std::string& path) {
  static const std::regex special(R"([.^$|()\[\]{}*+?\\])");
  return std::regex_replace(path, special, R"(\$&)");
}

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

// The handlers' view of a request. Pre-routing runs before the body is read, so there it has none yet.
HttpRequest to_exchange(const httplib::Request& req) {
  HttpRequest r;
  r.method = req.method;
  r.path = req.path;
  r.params = {req.params.begin(), req.params.end()};
  r.headers = {req.headers.begin(), req.headers.end()};
  r.ranges.assign(req.ranges.begin(), req.ranges.end());
  r.body = req.body;
  if (t_connection) r.client_gone = t_connection->client_gone;
  return r;
}

// Writes a handler's answer into cpp-httplib's response. A status of 206 leaves the slicing of the body to
// cpp-httplib (it applies the request's single range); a body stream becomes a chunked content provider.
void send(HttpResponse answer, httplib::Response& res) {
  res.status = answer.status;
  for (auto& [name, value] : answer.headers) res.set_header(name, value);
  if (answer.status == 304) return;  // no body, and no Content-Type of a body not sent
  if (!answer.stream) {
    res.set_content(std::move(answer.body), answer.content_type);
    return;
  }
  // cpp-httplib calls the provider until it signals done(); the stream writes the whole body in one call.
  auto provider = [stream = std::move(answer.stream)](std::size_t, httplib::DataSink& sink) {
    const ChunkSink write = [&sink](std::string_view chunk) { return sink.write(chunk.data(), chunk.size()); };
    if (!stream(write)) return false;  // client gone: cpp-httplib closes the connection
    sink.done();
    return true;
  };
  res.set_chunked_content_provider(answer.content_type, std::move(provider));
}

// A refused request ends its connection: cpp-httplib writes Connection: close when the request asks for it
// (the request is a local of its process_request), and the worker then closes the socket.
void close_after_response(const httplib::Request& req) {
  auto& mutable_req = const_cast<httplib::Request&>(req);
  mutable_req.headers.erase("Connection");
  mutable_req.headers.emplace("Connection", "close");
  t_close_after = true;
}

}  // namespace

// cpp-httplib's server with its connection handling replaced: process_and_close_socket (virtual in 0.11.4)
// gives each accepted socket to the reactor, and serve() runs cpp-httplib's request processing over one
// complete request.
class ReactorServer : public httplib::Server {
 public:
  std::function<void(int fd)> adopt;

  // cpp-httplib listens with a backlog of 5: a burst of connects would wait for SYN retries (seconds).
  // listen() again on the bound socket only raises the backlog.
  void widen_backlog(int backlog) { ::listen(svr_sock_, backlog); }

  // True when the connection may carry another request.
  bool serve(const ConnectionRequest& request, bool close_connection, int write_timeout_ms) {
    RequestStream stream(request, write_timeout_ms);
    t_connection = &request;
    t_close_after = false;
    t_routed = false;
    bool client_closes = false;
    const bool ok = process_request(stream, close_connection, client_closes, nullptr);
    const bool sent = stream.flush();
    t_connection = nullptr;
    return ok && sent && t_routed && !client_closes && !close_connection && !t_close_after;
  }

 private:
  bool process_and_close_socket(socket_t sock) override {
    adopt(sock);
    return true;
  }
};

HttpServer::HttpServer(ServerOptions options)
    : options_(std::move(options)), server_(std::make_unique<ReactorServer>()) {
  api_ = std::make_unique<ApiHandlers>(options_, metrics_, draining_, abort_work_);
  install();
  ReactorLimits limits;
  limits.max_header_bytes = options_.max_header_bytes;
  limits.max_headers = static_cast<std::size_t>(options_.max_headers);
  limits.max_body = options_.max_body;
  limits.request_read_timeout = options_.request_read_timeout;
  limits.keep_alive_timeout = options_.keep_alive_seconds;
  limits.max_connections = options_.max_connections;
  limits.max_connections_per_client = options_.max_connections_per_client;
  limits.workers = options_.threads;
  limits.health_workers = 2;
  ConnectionReactor::Routing routing;
  routing.is_health = [](std::string_view path) { return path == "/livez" || path == "/readyz"; };
  // API answers are never byte ranges; static files keep theirs.
  routing.ignores_range = [](std::string_view path) { return path != "/" && path_is_routed(std::string(path)); };
  auto serve = [this](const ConnectionRequest& request) {
    return server_->serve(request, draining_.load(), 5000);
  };
  auto refused = [this](int status, std::string_view code) {
    metrics_.rejected(std::string(code));
    metrics_.request_finished("unparsed", "-", status, 0.0);
  };
  reactor_ = std::make_unique<ConnectionReactor>(limits, std::move(routing), std::move(serve), std::move(refused));
  server_->adopt = [this](int fd) { reactor_->adopt(fd); };
}

HttpServer::~HttpServer() {
  stop();
  if (thread_.joinable()) thread_.join();
}

void HttpServer::install() {
  auto& svr = *server_;
  svr.new_task_queue = [] { return new InlineTaskQueue(); };
  // SO_REUSEADDR only: cpp-httplib's default adds SO_REUSEPORT, which lets a second server share the port.
  svr.set_socket_options([](socket_t sock) {
    const int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  svr.set_payload_max_length(options_.max_body);
  svr.set_read_timeout(5, 0);
  svr.set_write_timeout(5, 0);
  svr.set_keep_alive_timeout(options_.keep_alive_seconds);
  svr.set_keep_alive_max_count(100);
  svr.set_tcp_nodelay(true);
  svr.set_default_headers({{"X-Content-Type-Options", "nosniff"}});

  svr.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
    t_context = RequestContext{true, Clock::now(), "", ""};
    t_routed = true;
    const std::string given = req.get_header_value("X-Request-Id");
    t_context.id = valid_request_id(given) ? given : generate_request_id();
    res.set_header("X-Request-Id", t_context.id);

    const RouteSpec* route = find_route(req.method, req.path);
    t_context.route = route ? route->path : (path_is_routed(req.path) ? req.path : "static");
    auto refuse = [&](int status, const std::string& code, const std::string& message) {
      metrics_.rejected(code);
      close_after_response(req);
      send(error_response(status, code, "", message), res);
      return httplib::Server::HandlerResponse::Handled;
    };
    if (!route && path_is_routed(req.path)) {
      std::string allow;
      for (const auto& r : route_table()) {
        if (r.path == req.path) allow += (allow.empty() ? "" : ", ") + r.method;
      }
      res.set_header("Allow", allow);
      return refuse(405, "method_not_allowed", req.method + " is not allowed on " + req.path + " (allowed: " + allow + ")");
    }
    if (!route && req.method != "GET" && req.method != "HEAD") {
      return refuse(404, "not_found", "no such route: " + req.method + " " + req.path);
    }
    const BodyKind kind = route ? route->body : BodyKind::none;
    if (auto rejection = check_body_rules(to_exchange(req), kind, options_.max_body)) {
      return refuse(rejection->status, rejection->code, rejection->message);
    }
    if (route && route->long_work) {
      if (auto rejection = check_same_origin(to_exchange(req))) {
        return refuse(rejection->status, rejection->code, rejection->message);
      }
    }
    if (kind == BodyKind::json && req.get_header_value("Content-Type").find("application/x-www-form-urlencoded") == 0) {
      // What curl -d sends. The body is read as JSON all the same; relabelled here (before cpp-httplib reads
      // the body) because cpp-httplib refuses form bodies above 8192 bytes and parses them into parameters.
      auto& mutable_req = const_cast<httplib::Request&>(req);
      mutable_req.headers.erase("Content-Type");
      mutable_req.headers.emplace("Content-Type", "application/json");
    }
    if (draining_.load() && !(route && route->serves_while_draining)) {
      res.set_header("Retry-After", "1");
      return refuse(503, "shutting_down", "the server is shutting down");
    }
    return httplib::Server::HandlerResponse::Unhandled;
  });

  for (const auto& route : route_table()) {
    auto handler = [this, answer = route.handler](const httplib::Request& req, httplib::Response& res) {
      send(respond(answer, req), res);
    };
    const std::string pattern = regex_escape(route.path);
    if (route.method == "GET") svr.Get(pattern, handler);
    else svr.Post(pattern, handler);
    registered_.emplace_back(route.method, route.path);
  }
  // Everything else under / is a static file (or a JSON 404).
  svr.Get("/.*", [this](const httplib::Request& req, httplib::Response& res) {
    send(respond(&ApiHandlers::static_file, req), res);
  });

  // Runs for every status >= 400: fill in a JSON body where no handler wrote one (404, 400 from the parser).
  svr.set_error_handler(httplib::Server::HandlerWithResponse([](const httplib::Request& req, httplib::Response& res) {
    if (!res.body.empty() || res.is_chunked_content_provider_) return httplib::Server::HandlerResponse::Unhandled;
    std::string code = "error";
    std::string message = "the request could not be served";
    switch (res.status) {
      case 400: code = "bad_request"; message = "the request is not valid HTTP"; break;
      case 404: code = "not_found"; message = "no such route or file: " + req.path; break;
      case 413: code = "body_too_large"; message = "the request body is too large"; break;
      case 414: code = "uri_too_long"; message = "the request URI is too long"; break;
      case 416: code = "range_not_satisfiable"; message = "the Range header cannot be satisfied"; break;
      default: break;
    }
    send(error_response(res.status, code, "", message), res);
    return httplib::Server::HandlerResponse::Handled;
  }));

  // Without this cpp-httplib 0.11.4 puts the exception text into a response header (CVE-2026-28434).
  svr.set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr) {
    res.headers.erase("Content-Type");
    send(error_response(500, "internal_error", "", "internal error"), res);
  });

  svr.set_logger([this](const httplib::Request& req, const httplib::Response& res) {
    const bool known = t_context.active;
    const double seconds = known ? std::chrono::duration<double>(Clock::now() - t_context.start).count() : 0.0;
    const std::string route = known ? t_context.route : "unparsed";
    const std::string id = known ? t_context.id : generate_request_id();
    t_context.active = false;
    metrics_.request_finished(route, method_label(req.method), res.status, seconds);
    if (options_.log) {
      json line{{"time", utc_now()},    {"request_id", id},  {"method", req.method},
                {"path", req.path},     {"route", route},    {"status", res.status},
                {"seconds", seconds},   {"remote", req.remote_addr}};
      *options_.log << dump(line) + "\n" << std::flush;
    }
  });
}

// Handler exceptions that name an HTTP refusal become error responses; anything else reaches the exception
// handler above (500).
HttpResponse HttpServer::respond(RouteHandler handler, const httplib::Request& req) {
  try {
    return ((*api_).*handler)(to_exchange(req));
  } catch (const ApiError&) {
    return error_response(std::current_exception());
  } catch (const RequestError&) {
    return error_response(std::current_exception());
  }
}

int HttpServer::bind() {
  if (options_.port == 0) {
    port_ = server_->bind_to_any_port(options_.host);
    if (port_ <= 0) throw std::runtime_error("cannot bind " + options_.host + " to any port");
  } else {
    if (!server_->bind_to_port(options_.host, options_.port)) {
      throw std::runtime_error("cannot listen on " + options_.host + ":" + std::to_string(options_.port) +
                               " (the port is in use by another process, or the address is not available)");
    }
    port_ = options_.port;
  }
  server_->widen_backlog(1024);
  return port_;
}

void HttpServer::listen() { server_->listen_after_bind(); }

int HttpServer::start_background() {
  const int port = bind();
  thread_ = std::thread([this] { listen(); });
  // cpp-httplib has no wait_until_ready: poll is_running().
  for (int i = 0; i < 2000 && !server_->is_running(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  return port;
}

void HttpServer::drain_and_stop(double limit_seconds) {
  const auto start = Clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  draining_ = true;
  const double grace = std::min(options_.shutdown_grace, limit_seconds / 2);
  while (metrics_.work_in_flight() > 0 && elapsed() < grace) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  // Past the grace: cancel what still runs; streams end with a shutting_down error record.
  abort_work_ = true;
  while (metrics_.work_in_flight() > 0 && elapsed() < limit_seconds) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  stop();
}

void HttpServer::stop() {
  if (server_ && server_->is_running()) server_->stop();
  if (thread_.joinable() && thread_.get_id() != std::this_thread::get_id()) thread_.join();
  if (reactor_) reactor_->stop();
}

}  // namespace lienewton::service

namespace lienewton::service {

int healthcheck(const ServerOptions& options) {
  // 0.0.0.0 / :: are listen addresses, not destinations.
  const std::string host = options.host == "0.0.0.0" ? "127.0.0.1" : options.host == "::" ? "::1" : options.host;
  httplib::Client client(host, options.port);
  client.set_connection_timeout(2, 0);
  client.set_read_timeout(2, 0);
  auto res = client.Get("/livez");
  return res && res->status == 200 ? 0 : 1;
}

}  // namespace lienewton::service
