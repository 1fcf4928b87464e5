#include "server/http_server.hpp"

#include "server/httplib_include.hpp"

#include <strings.h>
#include <sys/socket.h>

#include <chrono>
#include <condition_variable>
#include <ctime>
#include <deque>
#include <limits>
#include <mutex>
#include <optional>
#include <regex>
#include <stdexcept>
#include <unordered_map>

#include "server/api_handlers.hpp"
#include "server/disconnect_watch.hpp"
#include "server/http_errors.hpp"
#include "server/request_limits.hpp"
#include "server/routes.hpp"
#include "core/request_error.hpp"

namespace lienewton::service {

using Clock = std::chrono::steady_clock;

// The queue behind cpp-httplib's accept loop. Each accepted connection is one task that holds a worker until
// the connection closes. `workers` threads serve the main lane; beyond `max_queued` waiting connections, new
// ones go to a small overflow lane whose requests are answered 503 at once (its threads are recognised by id
// in pre-routing), and beyond `max_connections` held connections, enqueue() waits, so that accept() stops and
// new connections wait in the kernel's backlog instead of taking descriptors.
struct WorkerLanes {
  std::mutex mutex;
  // One queue and wake-up signal per lane: each new connection wakes one worker of its own lane, not every
  // idle worker (a flood of connections would otherwise wake all of them once per connection).
  struct Lane {
    std::deque<std::function<void()>> jobs;
    std::condition_variable work;
  };
  std::condition_variable room;
  Lane main_lane;
  Lane overflow_lane;
  std::vector<std::thread::id> overflow_ids;
  std::size_t held = 0;  // connections queued or being served
  bool stopping = false;  // the server is stopping: enqueue() no longer waits
  bool shutdown = false;  // the accept loop has ended: workers finish what is queued and exit

  bool on_overflow_thread() {
    const std::lock_guard<std::mutex> lock(mutex);
    for (const auto& id : overflow_ids) {
      if (id == std::this_thread::get_id()) return true;
    }
    return false;
  }
  void stop_waiting() {
    {
      const std::lock_guard<std::mutex> lock(mutex);
      stopping = true;
    }
    room.notify_all();
  }
};

namespace {

constexpr int kOverflowWorkers = 2;
constexpr std::size_t kMaxHeaderFields = 100;

class WorkerQueue : public httplib::TaskQueue {
 public:
  WorkerQueue(std::shared_ptr<WorkerLanes> lanes, int workers, std::size_t max_queued, std::size_t max_connections)
      : lanes_(std::move(lanes)), max_queued_(max_queued), max_connections_(max_connections) {
    {
      const std::lock_guard<std::mutex> lock(lanes_->mutex);
      lanes_->shutdown = false;
      lanes_->stopping = false;
      lanes_->overflow_ids.clear();
    }
    for (int i = 0; i < workers; ++i) threads_.emplace_back([this] { run(lanes_->main_lane); });
    for (int i = 0; i < kOverflowWorkers; ++i) {
      threads_.emplace_back([this] { run(lanes_->overflow_lane); });
      const std::lock_guard<std::mutex> lock(lanes_->mutex);
      lanes_->overflow_ids.push_back(threads_.back().get_id());
    }
  }

  void enqueue(std::function<void()> fn) override {
    WorkerLanes::Lane* lane = nullptr;
    {
      std::unique_lock<std::mutex> lock(lanes_->mutex);
      lanes_->room.wait(lock, [&] { return lanes_->held < max_connections_ || lanes_->stopping; });
      ++lanes_->held;
      lane = lanes_->main_lane.jobs.size() < max_queued_ ? &lanes_->main_lane : &lanes_->overflow_lane;
      lane->jobs.push_back(std::move(fn));
    }
    lane->work.notify_one();
  }

  void shutdown() override {
    {
      const std::lock_guard<std::mutex> lock(lanes_->mutex);
      lanes_->shutdown = true;
    }
    lanes_->main_lane.work.notify_all();
    lanes_->overflow_lane.work.notify_all();
    for (auto& t : threads_) t.join();
  }

 private:
  void run(WorkerLanes::Lane& lane) {
    for (;;) {
      std::function<void()> fn;
      {
        std::unique_lock<std::mutex> lock(lanes_->mutex);
        lane.work.wait(lock, [&] { return !lane.jobs.empty() || lanes_->shutdown; });
        if (lane.jobs.empty()) return;
        fn = std::move(lane.jobs.front());
        lane.jobs.pop_front();
      }
      fn();
      {
        const std::lock_guard<std::mutex> lock(lanes_->mutex);
        --lanes_->held;
      }
      lanes_->room.notify_one();
    }
  }

  std::shared_ptr<WorkerLanes> lanes_;
  std::size_t max_queued_;
  std::size_t max_connections_;
  std::vector<std::thread> threads_;
};

}  // namespace

// When each request's pre-routing began, for the logger's latency and request id. cpp-httplib hands pre-routing,
// the handler and the logger the same Request object, so its address names the request until the logger ends it.
class RequestClocks {
 public:
  struct Entry {
    Clock::time_point start;
    std::string id;
  };
  void begin(const httplib::Request& req, std::string id) {
    const std::lock_guard<std::mutex> lock(mutex_);
    entries_[&req] = Entry{Clock::now(), std::move(id)};
  }
  // The entry of a request pre-routing saw, removed; nullopt for a request cpp-httplib could not parse.
  std::optional<Entry> end(const httplib::Request& req) {
    const std::lock_guard<std::mutex> lock(mutex_);
    auto found = entries_.find(&req);
    if (found == entries_.end()) return std::nullopt;
    Entry entry = std::move(found->second);
    entries_.erase(found);
    return entry;
  }

 private:
  std::mutex mutex_;
  std::unordered_map<const httplib::Request*, Entry> entries_;
};

namespace {

// The methods metrics may name; anything else is counted as "other" (label values from a fixed set).
std::string method_label(const std::string& method) {
  static const char* const kKnown[] = {"GET", "HEAD", "POST", "PUT", "DELETE", "OPTIONS", "PATCH", "CONNECT", "TRACE"};
  for (const char* m : kKnown) {
    if (method == m) return method;
  }
  return method.empty() ? "-" : "other";
}

std::string route_label(const httplib::Request& req) {
  if (req.method.empty()) return "unparsed";
  const RouteSpec* route = find_route(req.method, req.path);
  return route ? route->path : (path_is_routed(req.path) ? req.path : "static");
}

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

// Header fields whose name or value holds CR, LF or NUL: a bare CR inside a line, or one cpp-httplib decoded
// from %0D, %0A or %00 (it percent-decodes header values). nginx refuses the raw forms with 400 too. Referer is
// the page's own address, whose query may well hold an encoded newline (the dashboard keeps a program g in
// it); the server never reads it.
bool has_control_bytes(const httplib::Headers& headers) {
  auto bad = [](const std::string& s) { return s.find_first_of(std::string("\r\n\0", 3)) != std::string::npos; };
  for (const auto& [name, value] : headers) {
    if (bad(name) || (bad(value) && strcasecmp(name.c_str(), "Referer") != 0)) return true;
  }
  return false;
}

// Static files answer a byte range, "/" included (a route only so that the OpenAPI document lists it); API
// answers are never ranges: under a Range they go out whole, so no range is refused there.
bool serves_byte_ranges(const RouteSpec* route) { return !route || route->handler == &ApiHandlers::static_file; }

// The handlers' view of a request.
HttpRequest to_exchange(const httplib::Request& req, std::string client, std::string body = {}) {
  HttpRequest r;
  r.method = req.method;
  r.path = req.path;
  r.params = {req.params.begin(), req.params.end()};
  r.headers = {req.headers.begin(), req.headers.end()};
  r.ranges.assign(req.ranges.begin(), req.ranges.end());
  r.body = std::move(body);
  r.client = std::move(client);
  return r;
}

// A long request learns its connection's socket, to notice a client that leaves (disconnect_watch.hpp).
HttpRequest with_socket(HttpRequest r, const httplib::Request& req, bool long_work) {
  if (long_work) r.socket = connection_socket(req.remote_addr, req.remote_port, req.local_port);
  return r;
}

// cpp-httplib 0.11.4 applies a request's Range to any body it sends, error bodies included, but sends a chunked
// provider's body whole: so a body that must not be sliced goes out chunked.
void set_whole_body(httplib::Response& res, std::string body, const std::string& content_type) {
  res.body.clear();
  res.headers.erase("Content-Type");
  res.set_chunked_content_provider(content_type.c_str(), [body = std::move(body)](std::size_t, httplib::DataSink& sink) {
    if (!body.empty() && !sink.write(body.data(), body.size())) return false;
    sink.done();
    return true;
  });
}

// Writes a handler's answer into cpp-httplib's response. A status of 206 leaves the slicing of the body to
// cpp-httplib (it applies the request's single range); `whole` sends the body unsliced whatever the Range; a
// body stream becomes a chunked content provider.
void send(HttpResponse answer, httplib::Response& res, bool whole) {
  res.status = answer.status;
  for (auto& [name, value] : answer.headers) res.set_header(name, value);
  if (answer.status == 304) return;  // no body, and no Content-Type of a body not sent
  if (!answer.stream) {
    if (whole && answer.status < 400) set_whole_body(res, std::move(answer.body), answer.content_type);
    else res.set_content(std::move(answer.body), answer.content_type);
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

}  // namespace

HttpServer::HttpServer(ServerOptions options)
    : options_(std::move(options)), server_(std::make_unique<httplib::Server>()),
      lanes_(std::make_shared<WorkerLanes>()), clocks_(std::make_unique<RequestClocks>()) {
  api_ = std::make_unique<ApiHandlers>(options_, metrics_, draining_, abort_work_);
  install();
}

HttpServer::~HttpServer() {
  stop();
  if (thread_.joinable()) thread_.join();
}

std::string HttpServer::client_address(const httplib::Request& req) const {
  for (const auto& front : options_.trusted_fronts) {
    if (req.remote_addr != front) continue;
    const std::string forwarded = req.get_header_value("X-Real-IP");
    const bool plausible = !forwarded.empty() && forwarded.size() <= 45 &&
                           forwarded.find_first_not_of("0123456789abcdefABCDEF:.") == std::string::npos;
    if (plausible) return forwarded;
  }
  return req.remote_addr;
}

void HttpServer::install() {
  auto& svr = *server_;
  svr.new_task_queue = [this] {
    return new WorkerQueue(lanes_, options_.threads, static_cast<std::size_t>(options_.effective_max_queued()),
                           static_cast<std::size_t>(options_.max_connections));
  };
  // SO_REUSEADDR only: cpp-httplib's default adds SO_REUSEPORT, which lets a second server share the port.
  // The socket is kept to widen cpp-httplib's listen backlog of 5 after bind().
  svr.set_socket_options([this](socket_t sock) {
    const int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    listen_fd_ = sock;
  });
  svr.set_payload_max_length(options_.max_body);
  const auto seconds = static_cast<time_t>(options_.read_timeout);
  const auto micros = static_cast<time_t>((options_.read_timeout - static_cast<double>(seconds)) * 1e6);
  svr.set_read_timeout(seconds, micros);
  svr.set_write_timeout(seconds, micros);
  // One request per connection: cpp-httplib 0.11.4 would read a refused request's unread body as the next
  // request of a kept-alive connection (and drops pipelined requests it has read ahead), so every answer says
  // Connection: close and the connection ends with it. Keep-alive towards browsers is the front's job.
  svr.set_keep_alive_max_count(1);
  svr.set_keep_alive_timeout(options_.idle_seconds);
  svr.set_tcp_nodelay(true);
  svr.set_default_headers({{"X-Content-Type-Options", "nosniff"}});

  svr.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
    const std::string given = req.get_header_value("X-Request-Id");
    const std::string id = valid_request_id(given) ? given : generate_request_id();
    clocks_->begin(req, id);
    res.set_header("X-Request-Id", id);

    const RouteSpec* route = find_route(req.method, req.path);
    auto refuse = [&](int status, const std::string& code, const std::string& message) {
      metrics_.rejected(code);
      send(error_response(status, code, "", message), res, false);
      return httplib::Server::HandlerResponse::Handled;
    };
    // The overflow lane still answers /livez: the process is alive, only busy.
    if (lanes_->on_overflow_thread() && !(route && route->path == "/livez")) {
      res.set_header("Retry-After", "1");
      return refuse(503, "server_busy", "the server has more connections waiting than it serves; retry shortly");
    }
    // cpp-httplib 0.11.4 caps a header line (8 KB) but not their number; it adds four of its own (REMOTE_ADDR...).
    if (req.headers.size() > kMaxHeaderFields + 4) {
      return refuse(431, "too_many_headers", "a request may carry at most " + std::to_string(kMaxHeaderFields) + " header fields");
    }
    if (has_control_bytes(req.headers)) {
      return refuse(400, "invalid_header", "a header field holds a CR, LF or NUL byte");
    }
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
    HttpRequest request = to_exchange(req, client_address(req));
    if (!serves_byte_ranges(route)) request.ranges.clear();
    // A JSON body beyond the cap is left to cpp-httplib, which reads and discards it and answers 413: refused
    // here, it would stay unread, and closing a socket with unread bytes resets the connection before the
    // client has read the answer.
    const std::size_t cap = kind == BodyKind::json ? std::numeric_limits<std::size_t>::max() : options_.max_body;
    if (auto rejection = check_body_rules(request, kind, cap)) {
      return refuse(rejection->status, rejection->code, rejection->message);
    }
    if (route && route->long_work) {
      if (auto rejection = check_same_origin(request)) {
        return refuse(rejection->status, rejection->code, rejection->message);
      }
    }
    if (draining_.load() && !(route && route->serves_while_draining)) {
      res.set_header("Retry-After", "1");
      return refuse(503, "shutting_down", "the server is shutting down");
    }
    return httplib::Server::HandlerResponse::Unhandled;
  });

  // Expect: 100-continue: a body announced too large (or otherwise refused) is refused before it is sent.
  svr.set_expect_100_continue_handler([this](const httplib::Request& req, httplib::Response& res) {
    const RouteSpec* route = find_route(req.method, req.path);
    HttpRequest request = to_exchange(req, client_address(req));
    if (!serves_byte_ranges(route)) request.ranges.clear();
    if (auto rejection = check_body_rules(request, route ? route->body : BodyKind::none, options_.max_body)) {
      metrics_.rejected(rejection->code);
      send(error_response(rejection->status, rejection->code, "", rejection->message), res, false);
      return rejection->status;
    }
    return 100;
  });

  for (const auto& route : route_table()) {
    const std::string pattern = regex_escape(route.path);
    if (route.method == "GET") {
      const bool ranges = serves_byte_ranges(&route);
      svr.Get(pattern, [this, answer = route.handler, ranges, long_work = route.long_work](const httplib::Request& req,
                                                                                           httplib::Response& res) {
        send(respond(answer, with_socket(to_exchange(req, client_address(req)), req, long_work)), res,
             !ranges && !req.ranges.empty());
      });
    } else {
      // Read through a content reader: cpp-httplib's own body reading parses form bodies (what curl -d sends)
      // into parameters and refuses them beyond 8192 bytes; these bodies are JSON whatever their label.
      svr.Post(pattern, [this, answer = route.handler, long_work = route.long_work](
                            const httplib::Request& req, httplib::Response& res, const httplib::ContentReader& read) {
        std::string body;
        const bool complete = read([&body](const char* data, std::size_t size) {
          body.append(data, size);
          return true;
        });
        if (!complete && res.status == 413) {
          metrics_.rejected("body_too_large");
          send(error_response(413, "body_too_large", "", "the request body is larger than the limit of " +
                                                            std::to_string(options_.max_body) + " bytes"), res, false);
          return;
        }
        if (!complete) {
          send(error_response(400, "incomplete_body", "", "the request body did not arrive in full"), res, false);
          return;
        }
        send(respond(answer, with_socket(to_exchange(req, client_address(req), std::move(body)), req, long_work)), res,
             !req.ranges.empty());
      });
    }
    registered_.emplace_back(route.method, route.path);
  }
  // Everything else under / is a static file (or a JSON 404).
  svr.Get("/.*", [this](const httplib::Request& req, httplib::Response& res) {
    send(respond(&ApiHandlers::static_file, to_exchange(req, client_address(req))), res, false);
  });

  // Runs for every status >= 400, before cpp-httplib applies ranges: fills in a JSON body where nothing wrote
  // one (404, and 400/414/416 from cpp-httplib's parser), and keeps error bodies whole under any Range.
  svr.set_error_handler(httplib::Server::HandlerWithResponse([](const httplib::Request& req, httplib::Response& res) {
    if (res.body.empty()) {  // streams, the only answers without a body here, never fail with a status
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
      send(error_response(res.status, code, "", message), res, false);
    }
    if (!req.ranges.empty() && !res.body.empty()) {
      std::string body = std::move(res.body);
      set_whole_body(res, std::move(body), res.get_header_value("Content-Type"));
    }
    return httplib::Server::HandlerResponse::Handled;
  }));
  // With several ranges cpp-httplib relabels any answer multipart/byteranges; the only such answers here are
  // whole JSON refusals (check_body_rules: 416).
  svr.set_post_routing_handler([](const httplib::Request& req, httplib::Response& res) {
    if (req.ranges.size() > 1 && res.status != 206) {
      res.headers.erase("Content-Type");
      res.set_header("Content-Type", "application/json");
    }
  });

  // Without this cpp-httplib 0.11.4 puts the exception text into a response header (CVE-2026-28434).
  svr.set_exception_handler([](const httplib::Request& req, httplib::Response& res, std::exception_ptr error) {
    log_internal_error(req.method + " " + req.path, error);
    res.headers.erase("Content-Type");
    send(error_response(500, "internal_error", "", "internal error"), res, false);
  });

  svr.set_logger([this](const httplib::Request& req, const httplib::Response& res) {
    const auto clock = clocks_->end(req);
    const double seconds = clock ? std::chrono::duration<double>(Clock::now() - clock->start).count() : 0.0;
    const std::string route = clock ? route_label(req) : "unparsed";
    metrics_.request_finished(route, method_label(req.method), res.status, seconds);
    if (options_.log) {
      json line{{"time", utc_now()},    {"request_id", clock ? clock->id : generate_request_id()},
                {"method", req.method}, {"path", req.path},
                {"route", route},       {"status", res.status},
                {"seconds", seconds},   {"remote", client_address(req)}};
      *options_.log << dump(line) + "\n" << std::flush;
    }
  });
}

// Handler exceptions that name an HTTP refusal become error responses; anything else reaches the exception
// handler above (500).
HttpResponse HttpServer::respond(RouteHandler handler, const HttpRequest& req) {
  try {
    return ((*api_).*handler)(req);
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
  // cpp-httplib listens with a backlog of 5: a burst of connects would wait for SYN retries (seconds).
  // listen() again on the bound socket only raises the backlog.
  if (listen_fd_ >= 0) ::listen(listen_fd_, 1024);
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
  // An accept loop waiting for room in the queue must see the listener close.
  lanes_->stop_waiting();
  if (server_ && server_->is_running()) server_->stop();
  if (thread_.joinable() && thread_.get_id() != std::this_thread::get_id()) thread_.join();
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
