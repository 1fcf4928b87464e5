// lienewton-server: flags/env -> HttpServer; SIGTERM/SIGINT are blocked in every thread and taken by sigwait
// in a dedicated thread, because stopping the HTTP server is not async-signal-safe.
#include <malloc.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <pthread.h>
#include <signal.h>
#include <sys/resource.h>
#include <unistd.h>
#include <thread>

#include "server/http_server.hpp"
#include "server/server_options.hpp"

namespace {

// Descriptors beside the connections: the listener, logs, static files, the render contexts.
constexpr rlim_t kSpareDescriptors = 100;

// Raises the soft RLIMIT_NOFILE to what max_connections needs (up to the hard limit), and lowers
// max_connections below the limit when the hard limit is too small; returns the limit in force.
rlim_t fit_descriptor_limit(lienewton::service::ServerOptions& options) {
  rlimit limit{};
  if (getrlimit(RLIMIT_NOFILE, &limit) != 0) return 0;
  const rlim_t needed = static_cast<rlim_t>(options.max_connections) + kSpareDescriptors;
  if (limit.rlim_cur < needed) {
    limit.rlim_cur = std::min(needed, limit.rlim_max);
    setrlimit(RLIMIT_NOFILE, &limit);
    getrlimit(RLIMIT_NOFILE, &limit);
  }
  if (limit.rlim_cur < needed) {
    options.max_connections = static_cast<int>(std::max<rlim_t>(limit.rlim_cur, 2 * kSpareDescriptors) - kSpareDescriptors);
  }
  return limit.rlim_cur;
}

bool loopback(const std::string& host) {
  return host == "localhost" || host == "::1" || host.rfind("127.", 0) == 0;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace lienewton::service;
  // glibc gives each worker thread that allocates its own arena, up to 8 per core, and each keeps the pages its
  // requests touched: one arena per core keeps far less resident after a run of large requests (docs/service.md,
  // Memory, has the measurement). malloc_trim after the last request returns the rest.
  mallopt(M_ARENA_MAX, static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
  std::string message;
  bool help = false;
  auto parsed = parse_server_options(argc, argv, message, help);
  if (!parsed) {
    (help ? std::cout : std::cerr) << message << (help ? "" : "\n");
    return help ? 0 : 2;
  }
  ServerOptions options = *parsed;
  if (options.healthcheck) return healthcheck(options);

  // Before any thread exists, so that every thread inherits the mask.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGINT);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  std::signal(SIGPIPE, SIG_IGN);

  options.web_root = find_web_root(options.web_root, argc > 0 ? argv[0] : "");
  options.log = &std::cout;
  const rlim_t descriptors = fit_descriptor_limit(options);
  if (!loopback(options.host) && options.trusted_fronts.empty()) {
    std::cout << dump(json{{"event", "warning"},
                           {"message", "listening on " + options.host +
                                           " without a front: slow and idle clients hold this server's workers; "
                                           "put nginx in front (deploy/) and pass its address as --trusted-front"}})
              << std::endl;
  }
  try {
    HttpServer server(options);
    const int port = server.bind();
    std::cout << dump(json{{"event", "listening"}, {"host", options.host}, {"port", port},
                           {"threads", options.threads}, {"max_streams", options.effective_max_streams()},
                           {"max_connections", options.max_connections}, {"descriptor_limit", descriptors},
                           {"web_root", options.web_root}})
              << std::endl;
    std::thread waiter([&server, signals] {
      int sig = 0;
      sigwait(&signals, &sig);
      std::cout << dump(json{{"event", "draining"}, {"signal", sig == SIGTERM ? "SIGTERM" : "SIGINT"}}) << std::endl;
      server.drain_and_stop();
    });
    server.listen();
    // listen() also returns when the socket fails: wake the waiter so that the process can end.
    if (!server.draining()) kill(getpid(), SIGTERM);
    waiter.join();
    std::cout << dump(json{{"event", "stopped"}}) << std::endl;
  } catch (const std::exception& e) {
    std::cerr << "lienewton-server: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
