#include "server/connection_reactor.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <sys/epoll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cctype>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <optional>
#include <tuple>
#include <condition_variable>
#include <deque>
#include <map>
#include <mutex>
#include <thread>
#include <unordered_map>
#include <vector>

#include "server/http_errors.hpp"

namespace lienewton::service {
namespace {

using Clock = std::chrono::steady_clock;

// How long a refused or finished connection may still deliver (discarded) bytes after our last answer, so
// that closing with unread input does not reset the connection before the client has read that answer.
constexpr auto kLingerTime = std::chrono::seconds(1);
constexpr int kTickMilliseconds = 50;
// Connections beyond max_connections that are still read (for a health request) before any is refused at once.
constexpr int kHealthHeadroom = 64;

Clock::duration seconds(double s) {
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i]))) return false;
  }
  return true;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// RFC 9110 5.6.2 token characters: a header name with anything else (spaces before the colon) is refused.
bool is_token(std::string_view s) {
  if (s.empty()) return false;
  for (char c : s) {
    const bool ok = std::isalnum(static_cast<unsigned char>(c)) || std::string_view("!#$%&'*+-.^_`|~").find(c) != std::string_view::npos;
    if (!ok) return false;
  }
  return true;
}

const char* reason_phrase(int status) {
  switch (status) {
    case 400: return "Bad Request";
    case 408: return "Request Timeout";
    case 411: return "Length Required";
    case 413: return "Payload Too Large";
    case 431: return "Request Header Fields Too Large";
    case 503: return "Service Unavailable";
    default: return "Error";
  }
}

// A complete JSON error response that closes the connection.
std::string refusal_bytes(int status, std::string_view code, std::string_view message) {
  const HttpResponse res = error_response(status, code, "", message);
  std::string out = "HTTP/1.1 " + std::to_string(status) + " " + reason_phrase(status) + "\r\n";
  out += "Content-Type: application/json\r\nContent-Length: " + std::to_string(res.body.size()) + "\r\n";
  if (status == 503) out += "Retry-After: 1\r\n";
  out += "X-Content-Type-Options: nosniff\r\nConnection: close\r\n\r\n" + res.body;
  return out;
}

void send_all_nonblocking(int fd, std::string_view bytes) {
  // Small answers on a fresh socket buffer: one send normally takes all; what does not fit is dropped.
  while (!bytes.empty()) {
    const ssize_t n = ::send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL);
    if (n <= 0) return;
    bytes.remove_prefix(static_cast<std::size_t>(n));
  }
}

std::pair<std::string, int> address_of(const sockaddr_storage& addr) {
  char text[INET6_ADDRSTRLEN] = "";
  int port = 0;
  if (addr.ss_family == AF_INET) {
    const auto* a = reinterpret_cast<const sockaddr_in*>(&addr);
    inet_ntop(AF_INET, &a->sin_addr, text, sizeof text);
    port = ntohs(a->sin_port);
  } else if (addr.ss_family == AF_INET6) {
    const auto* a = reinterpret_cast<const sockaddr_in6*>(&addr);
    inet_ntop(AF_INET6, &a->sin6_addr, text, sizeof text);
    port = ntohs(a->sin6_port);
  }
  return {text, port};
}

// A fixed set of threads running queued tasks in order of arrival.
class WorkerPool {
 public:
  explicit WorkerPool(int threads) {
    for (int i = 0; i < threads; ++i) threads_.emplace_back([this] { run(); });
  }
  ~WorkerPool() { join(); }
  void post(std::function<void()> task) {
    {
      std::lock_guard lock(mutex_);
      tasks_.push_back(std::move(task));
    }
    wake_.notify_one();
  }
  void join() {
    {
      std::lock_guard lock(mutex_);
      closing_ = true;
    }
    wake_.notify_all();
    for (auto& t : threads_) {
      if (t.joinable()) t.join();
    }
  }

 private:
  void run() {
    for (;;) {
      std::function<void()> task;
      {
        std::unique_lock lock(mutex_);
        wake_.wait(lock, [this] { return closing_ || !tasks_.empty(); });
        if (tasks_.empty()) return;
        task = std::move(tasks_.front());
        tasks_.pop_front();
      }
      task();
    }
  }
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::function<void()>> tasks_;
  bool closing_ = false;
  std::vector<std::thread> threads_;
};

// What the reactor needs of a request head.
struct Head {
  std::size_t length = 0;  // bytes up to and including the blank line
  std::string path;
  std::size_t content_length = 0;
  bool expects_continue = false;
  std::string rewritten;   // the head as handed to the worker
};

struct Refusal {
  int status;
  std::string code;
  std::string message;
};

}  // namespace

struct ConnectionReactor::Impl {
  enum class State { reading, busy, lingering };
  struct Connection {
    int fd = -1;
    std::string ip;
    int port = 0;
    std::string local_ip;
    int local_port = 0;
    State state = State::reading;
    std::string in;                 // received, not yet served
    bool request_started = false;   // the current request's first byte has arrived
    bool sent_continue = false;
    bool peer_closed = false;       // read returned 0
    bool registered = false;        // in the epoll set
    int over_cap = 0;               // 1: beyond max_connections, 2: beyond max_connections_per_client
    Clock::time_point since;        // request start, idle start, or linger start
    std::shared_ptr<std::atomic<bool>> gone = std::make_shared<std::atomic<bool>>(false);
  };
  struct Completion {
    int fd;
    bool keep;
  };

  Impl(ReactorLimits l, Routing r, Serve s, OnRefusal o)
      : limits(l), routing(std::move(r)), serve(std::move(s)), on_refusal(std::move(o)),
        workers(l.workers), health_workers(l.health_workers) {
    epoll_fd = epoll_create1(EPOLL_CLOEXEC);
    wake_fd = eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
    epoll_event ev{};
    ev.events = EPOLLIN;
    ev.data.fd = wake_fd;
    epoll_ctl(epoll_fd, EPOLL_CTL_ADD, wake_fd, &ev);
    thread = std::thread([this] { loop(); });
  }

  ~Impl() {
    stop();
    ::close(wake_fd);
    ::close(epoll_fd);
  }

  void wake() {
    const std::uint64_t one = 1;
    [[maybe_unused]] const ssize_t n = ::write(wake_fd, &one, sizeof one);
  }

  void post_adopt(int fd) {
    {
      std::lock_guard lock(inbox_mutex);
      adopted.push_back(fd);
    }
    wake();
  }

  void post_completion(int fd, bool keep) {
    {
      std::lock_guard lock(inbox_mutex);
      completions.push_back({fd, keep});
    }
    wake();
  }

  void stop() {
    if (stopping.exchange(true)) {
      if (thread.joinable()) thread.join();
      return;
    }
    wake();
    if (thread.joinable()) thread.join();
    workers.join();
    health_workers.join();
    std::lock_guard lock(inbox_mutex);
    for (int fd : adopted) ::close(fd);  // accepted after the loop ended
    adopted.clear();
  }

  // ---------------------------------------------------------------- reactor thread
  void loop() {
    std::vector<epoll_event> events(256);
    for (;;) {
      const int n = epoll_wait(epoll_fd, events.data(), static_cast<int>(events.size()), kTickMilliseconds);
      for (int i = 0; i < n; ++i) {
        const int fd = events[static_cast<std::size_t>(i)].data.fd;
        if (fd == wake_fd) {
          std::uint64_t count;
          [[maybe_unused]] const ssize_t r = ::read(wake_fd, &count, sizeof count);
          continue;
        }
        auto it = connections.find(fd);
        if (it != connections.end()) on_event(*it->second, events[static_cast<std::size_t>(i)].events);
      }
      take_inbox();
      if (stopping.load()) {
        shut_everything_down();
        if (connections.empty()) return;
      }
      enforce_deadlines();
    }
  }

  void take_inbox() {
    std::vector<int> fds;
    std::vector<Completion> done;
    {
      std::lock_guard lock(inbox_mutex);
      fds.swap(adopted);
      done.swap(completions);
    }
    for (int fd : fds) accept_connection(fd);
    for (const auto& c : done) finish_request(c);
  }

  void accept_connection(int fd) {
    const int flags = fcntl(fd, F_GETFL, 0);
    fcntl(fd, F_SETFL, flags | O_NONBLOCK);
    auto conn = std::make_unique<Connection>();
    conn->fd = fd;
    sockaddr_storage addr{};
    socklen_t len = sizeof addr;
    if (getpeername(fd, reinterpret_cast<sockaddr*>(&addr), &len) == 0) std::tie(conn->ip, conn->port) = address_of(addr);
    len = sizeof addr;
    if (getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) == 0) {
      std::tie(conn->local_ip, conn->local_port) = address_of(addr);
    }
    conn->since = Clock::now();
    Connection& c = *conn;
    connections[fd] = std::move(conn);
    const bool over_total = active >= limits.max_connections;
    const bool over_client = per_client[c.ip] >= limits.max_connections_per_client;
    count_in(c);
    if (stopping.load()) {
      refuse(c, {503, "shutting_down", "the server is shutting down"});
    } else if (active > limits.max_connections + kHealthHeadroom) {
      refuse(c, too_many_connections(true));
    } else {
      // Beyond a cap a connection may still ask /livez or /readyz once; anything else gets 503.
      if (over_total || over_client) c.over_cap = over_total ? 1 : 2;
      watch(c, EPOLLIN | EPOLLRDHUP);
    }
  }

  static Refusal too_many_connections(bool total) {
    return total ? Refusal{503, "too_many_connections", "the server has too many open connections; retry shortly"}
                 : Refusal{503, "too_many_connections_per_client", "this client address has too many open connections"};
  }

  void count_in(const Connection& c) {
    ++active;
    ++per_client[c.ip];
    open_count.store(static_cast<int>(connections.size()));
  }

  void count_out(const Connection& c) {
    --active;
    if (--per_client[c.ip] <= 0) per_client.erase(c.ip);
  }

  void watch(Connection& c, std::uint32_t events) {
    epoll_event ev{};
    ev.events = events;
    ev.data.fd = c.fd;
    epoll_ctl(epoll_fd, c.registered ? EPOLL_CTL_MOD : EPOLL_CTL_ADD, c.fd, &ev);
    c.registered = true;
  }

  void unwatch(Connection& c) {
    if (c.registered) epoll_ctl(epoll_fd, EPOLL_CTL_DEL, c.fd, nullptr);
    c.registered = false;
  }

  void on_event(Connection& c, std::uint32_t events) {
    switch (c.state) {
      case State::busy:
        // The client hung up while its request is being served: cancel the work. The worker closes.
        if (events & (EPOLLRDHUP | EPOLLHUP | EPOLLERR)) {
          c.gone->store(true);
          unwatch(c);
        }
        return;
      case State::lingering:
        if (!drain_input(c)) close_connection(c);
        return;
      case State::reading:
        read_and_dispatch(c);
        return;
    }
  }

  // Reads and discards; false once the peer has closed or failed.
  bool drain_input(Connection& c) {
    char buf[16384];
    for (;;) {
      const ssize_t n = ::recv(c.fd, buf, sizeof buf, 0);
      if (n > 0) continue;
      return n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR);
    }
  }

  void read_and_dispatch(Connection& c) {
    char buf[16384];
    for (;;) {
      const ssize_t n = ::recv(c.fd, buf, sizeof buf, 0);
      if (n > 0) {
        if (!c.request_started) {
          c.request_started = true;
          c.since = Clock::now();
        }
        c.in.append(buf, static_cast<std::size_t>(n));
        if (advance(c)) return;  // dispatched, refused or closed: read no further for now
        continue;
      }
      if (n == 0) {
        c.peer_closed = true;
        close_connection(c);  // a request cut short, or an idle keep-alive client leaving
        return;
      }
      if (errno == EINTR) continue;
      if (errno != EAGAIN && errno != EWOULDBLOCK) close_connection(c);
      return;
    }
  }

  // Looks at the buffered bytes: dispatches a complete request, refuses a bad one, or waits for more.
  // Returns true when the connection left the reading state (or is gone).
  bool advance(Connection& c) {
    if (c.in.empty()) return false;
    if (!c.request_started) {
      c.request_started = true;
      c.since = Clock::now();
    }
    Head head;
    if (auto refusal = parse_head(c.in, head)) {
      refuse(c, *refusal);
      return true;
    }
    if (head.length == 0) return false;  // head incomplete
    const bool health = routing.is_health && routing.is_health(head.path);
    if (c.over_cap && !health) {
      refuse(c, too_many_connections(c.over_cap == 1));
      return true;
    }
    const std::size_t total = head.length + head.content_length;
    if (c.in.size() < total) {
      if (head.expects_continue && !c.sent_continue) {
        send_all_nonblocking(c.fd, "HTTP/1.1 100 Continue\r\n\r\n");
        c.sent_continue = true;
      }
      return false;
    }
    dispatch(c, head.rewritten + c.in.substr(head.length, head.content_length), health);
    c.in.erase(0, total);
    return true;
  }

  // Sets head.length = 0 while the head is incomplete; a refusal when it breaks a limit or the framing rules.
  std::optional<Refusal> parse_head(const std::string& in, Head& head) const {
    const std::size_t end = in.find("\r\n\r\n");
    if (end == std::string::npos) {
      if (in.size() > limits.max_header_bytes) return too_large();
      head.length = 0;
      return std::nullopt;
    }
    head.length = end + 4;
    if (head.length > limits.max_header_bytes) return too_large();
    std::string_view text(in.data(), end);
    const std::size_t line_end = text.find("\r\n");
    const std::string_view request_line = text.substr(0, line_end);
    const std::size_t sp1 = request_line.find(' ');
    const std::size_t sp2 = sp1 == std::string_view::npos ? sp1 : request_line.find(' ', sp1 + 1);
    if (sp2 == std::string_view::npos) return Refusal{400, "bad_request", "the request line is not valid HTTP"};
    const std::string_view target = request_line.substr(sp1 + 1, sp2 - sp1 - 1);
    head.path = std::string(target.substr(0, target.find('?')));
    const bool drop_range = routing.ignores_range && routing.ignores_range(head.path);

    head.rewritten.assign(request_line);
    head.rewritten += "\r\n";
    std::size_t count = 0;
    int lengths = 0;
    std::size_t pos = line_end == std::string_view::npos ? text.size() : line_end + 2;
    while (pos < text.size()) {
      std::size_t next = text.find("\r\n", pos);
      if (next == std::string_view::npos) next = text.size();
      const std::string_view line = text.substr(pos, next - pos);
      pos = next + 2;
      if (++count > limits.max_headers) {
        return Refusal{431, "too_many_headers",
                       "the request has more than " + std::to_string(limits.max_headers) + " header fields"};
      }
      const std::size_t colon = line.find(':');
      const std::string_view name = line.substr(0, colon);
      if (colon == std::string_view::npos || !is_token(name)) {
        return Refusal{400, "bad_header", "a header line is not a valid field"};
      }
      const std::string_view value = trim(line.substr(colon + 1));
      if (iequals(name, "Transfer-Encoding")) {
        return Refusal{411, "length_required", "request bodies must be sent with Content-Length, not Transfer-Encoding"};
      }
      if (iequals(name, "Content-Length")) {
        std::size_t length = 0;
        const auto [p, ec] = std::from_chars(value.data(), value.data() + value.size(), length);
        if (++lengths > 1 || value.empty() || ec != std::errc() || p != value.data() + value.size()) {
          return Refusal{400, "invalid_content_length", "Content-Length must be given once, as a number"};
        }
        if (length > limits.max_body) {
          return Refusal{413, "body_too_large",
                         "the request body is larger than the limit of " + std::to_string(limits.max_body) + " bytes"};
        }
        head.content_length = length;
      }
      if (iequals(name, "Expect")) {
        head.expects_continue = iequals(value, "100-continue");
        continue;  // answered here, never by the worker
      }
      if (drop_range && iequals(name, "Range")) continue;
      head.rewritten.append(line);
      head.rewritten += "\r\n";
    }
    head.rewritten += "\r\n";
    return std::nullopt;
  }

  Refusal too_large() const {
    return {431, "headers_too_large",
            "the request line and headers are larger than the limit of " + std::to_string(limits.max_header_bytes) +
                " bytes"};
  }

  void dispatch(Connection& c, std::string bytes, bool health) {
    c.state = State::busy;
    c.request_started = false;
    c.sent_continue = false;
    if (c.peer_closed) {
      unwatch(c);
    } else {
      watch(c, EPOLLRDHUP);
    }
    auto request = std::make_shared<ConnectionRequest>();
    request->fd = c.fd;
    request->remote_ip = c.ip;
    request->remote_port = c.port;
    request->local_ip = c.local_ip;
    request->local_port = c.local_port;
    request->bytes = std::move(bytes);
    request->client_gone = c.gone;
    auto task = [this, request] {
      bool keep = false;
      try {
        keep = serve(*request);
      } catch (...) {
        keep = false;  // serve writes its own error answers; anything escaping it ends the connection
      }
      post_completion(request->fd, keep);
    };
    (health ? health_workers : workers).post(std::move(task));
  }

  void finish_request(const Completion& done) {
    auto it = connections.find(done.fd);
    if (it == connections.end()) return;
    Connection& c = *it->second;
    if (!done.keep || c.gone->load() || c.peer_closed || c.over_cap || stopping.load()) {
      linger(c);
      return;
    }
    c.state = State::reading;
    c.since = Clock::now();
    watch(c, EPOLLIN | EPOLLRDHUP);
    // A pipelined request may already be buffered; otherwise wait for the socket.
    if (!advance(c)) read_and_dispatch(c);
  }

  void refuse(Connection& c, const Refusal& r) {
    if (on_refusal) on_refusal(r.status, r.code);
    send_all_nonblocking(c.fd, refusal_bytes(r.status, r.code, r.message));
    linger(c);
  }

  // Half-closes and discards input for a moment, then closes (see kLingerTime).
  void linger(Connection& c) {
    if (c.state == State::lingering) return;
    count_out(c);
    c.state = State::lingering;
    c.since = Clock::now();
    c.in.clear();
    c.in.shrink_to_fit();
    ::shutdown(c.fd, SHUT_WR);
    watch(c, EPOLLIN | EPOLLRDHUP);
  }

  void close_connection(Connection& c) {
    if (c.state != State::lingering) count_out(c);
    unwatch(c);
    const int fd = c.fd;
    ::close(fd);
    connections.erase(fd);  // destroys c
    open_count.store(static_cast<int>(connections.size()));
  }

  void enforce_deadlines() {
    const auto now = Clock::now();
    std::vector<Connection*> expired;
    for (auto& [fd, conn] : connections) {
      Connection& c = *conn;
      if (c.state == State::lingering && now - c.since > kLingerTime) expired.push_back(&c);
      if (c.state != State::reading) continue;
      const auto limit = c.request_started ? seconds(limits.request_read_timeout) : seconds(limits.keep_alive_timeout);
      if (now - c.since > limit) expired.push_back(&c);
    }
    for (Connection* c : expired) {
      if (c->state == State::reading && c->request_started) {
        refuse(*c, {408, "request_timeout",
                    "the request was not received within " + format_seconds(limits.request_read_timeout)});
      } else {
        close_connection(*c);
      }
    }
  }

  static std::string format_seconds(double s) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g s", s);
    return buf;
  }

  // At stop: idle and reading connections close at once; connections being served are cut so that their
  // writes fail and their work sees client_gone; they close when their worker returns.
  void shut_everything_down() {
    std::vector<Connection*> idle;
    for (auto& [fd, conn] : connections) {
      if (conn->state == State::busy) {
        if (!conn->gone->exchange(true)) ::shutdown(conn->fd, SHUT_RDWR);
      } else {
        idle.push_back(conn.get());
      }
    }
    for (Connection* c : idle) close_connection(*c);
  }

  ReactorLimits limits;
  Routing routing;
  Serve serve;
  OnRefusal on_refusal;
  int epoll_fd = -1;
  int wake_fd = -1;
  std::unordered_map<int, std::unique_ptr<Connection>> connections;  // reactor thread only
  std::map<std::string, int> per_client;                           // reactor thread only
  int active = 0;                                                   // connections not lingering
  std::atomic<int> open_count{0};
  std::mutex inbox_mutex;
  std::vector<int> adopted;
  std::vector<Completion> completions;
  std::atomic<bool> stopping{false};
  WorkerPool workers;
  WorkerPool health_workers;
  std::thread thread;
};

ConnectionReactor::ConnectionReactor(ReactorLimits limits, Routing routing, Serve serve, OnRefusal on_refusal)
    : impl_(std::make_unique<Impl>(limits, std::move(routing), std::move(serve), std::move(on_refusal))) {}

ConnectionReactor::~ConnectionReactor() = default;

void ConnectionReactor::adopt(int fd) { impl_->post_adopt(fd); }

void ConnectionReactor::stop() { impl_->stop(); }

int ConnectionReactor::open_connections() const { return impl_->open_count.load(); }

}  // namespace lienewton::service
