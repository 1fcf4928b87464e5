#pragma once
// Settings of lienewton-server: flags with LIENEWTON_* environment equivalents (flags win).
#include <cstddef>
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "server/json_codec.hpp"
#include "server/output_limits.hpp"

namespace lienewton::service {

struct ServerOptions {
  std::string host = "127.0.0.1";
  int port = 8080;                 // 0: any free port (tests)
  // Workers; each serves one connection at a time, from accept to close (a waiting or slow client holds one).
  int threads = 64;
  Limits limits;                   // max_n, max_iterations, grid caps
  OutputLimits output;             // numbers per result, pixels per image
  double request_timeout = 30;     // seconds per request, streams included
  // seconds a sweep (JSON, stream or heatmap render) may run: a stability map of hundreds of solves gets a budget
  // of its own, long enough for the default map (882 cells) on a busy 2-core machine
  double sweep_timeout = 120;
  std::string web_root;            // "" : found next to the binary or in the working directory
  std::size_t max_body = 1 << 20;  // bytes
  int max_streams = 6;             // concurrent long requests (streams, solves, renders); at most threads - 2
  int render_workers = 1;
  double shutdown_grace = 3;       // seconds open streams may still finish after SIGTERM before being cut
  int idle_seconds = 1;            // seconds a new connection may wait before its request starts
  double read_timeout = 5;         // seconds any one read or write of a request or answer may stall
  int max_connections = 512;       // accepted connections held at once; beyond it new ones wait in the backlog
  int max_queued = 0;              // connections waiting for a worker; more are answered 503; 0: 4 x threads
  // Addresses of the front (nginx): only connections from them may name the client with X-Real-IP.
  std::vector<std::string> trusted_fronts;
  bool healthcheck = false;        // --healthcheck: GET /livez of host:port and exit 0/1
  std::ostream* log = nullptr;     // one JSON line per request; nullptr: no log
  // Test hook: called with each progress record's index (iteration, cell, step, series) as it is produced.
  std::function<void(int)> on_progress;

  int effective_max_streams() const;
  // Long requests one client address may run at once: half the slots (at least one), so that one address
  // cannot take them all.
  int max_streams_per_client() const;
  int effective_max_queued() const { return max_queued > 0 ? max_queued : 4 * threads; }
};

// Parses argv and the environment. Returns nullopt and fills `message` on --help (exit 0) or on an error
// (exit 2); `help` tells which.
std::optional<ServerOptions> parse_server_options(int argc, const char* const* argv, std::string& message, bool& help);
std::string server_usage();

// The web root to serve: the option if set, else <exe>/../../web, <exe>/../web, <exe>/../share/lienewton/web
// or ./web, whichever holds index.html.
std::string find_web_root(const std::string& configured, const std::string& exe_path);

}  // namespace lienewton::service
