// lienewton-server: flags/env -> HttpServer; SIGTERM/SIGINT are blocked in every thread and taken by sigwait
// in a dedicated thread, because stopping the HTTP server is not async-signal-safe.
#include <csignal>
#include <cstdio>
#include <iostream>
#include <pthread.h>
#include <signal.h>
#include <unistd.h>
#include <thread>

#include "server/http_server.hpp"
#include "server/server_options.hpp"

int main(int argc, char** argv) {
  using namespace lienewton::service;
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
  try {
    HttpServer server(options);
    const int port = server.bind();
    std::cout << dump(json{{"event", "listening"}, {"host", options.host}, {"port", port},
                           {"threads", options.threads}, {"max_streams", options.effective_max_streams()},
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
