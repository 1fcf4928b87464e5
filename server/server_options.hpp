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
  int threads = 8;                 // workers serving complete requests (idle and slow connections hold none)
  Limits limits;                   // max_n, max_iterations, grid caps
  OutputLimits output;             // numbers per result, pixels per image
  double request_timeout = 30;     // seconds per request, streams included
  // seconds a sweep (JSON, stream or heatmap render) may run: a stability map of hundreds of solves gets a budget
  // of its own, long enough for the default map (882 cells) on a busy 2-core machine
  double sweep_timeout = 600;
  std::string web_root;            // "" : found next to the binary or in the working directory
  std::size_t max_body = 1 << 20;  // bytes
  int max_streams = 0;             // concurrent long requests (streams, solves, renders); 0: threads - 2
  int render_workers = 1;
  double shutdown_grace = 3;       // seconds open streams may still finish after SIGTERM before being cut
  int keep_alive_seconds = 2;      // idle seconds between requests on one connection
  double request_read_timeout = 10;  // seconds from a request's first byte to its last; then 408
  std::size_t max_header_bytes = 16384;  // request line + headers; larger gets 431
  int max_headers = 100;           // header fields; more get 431
  int max_connections = 512;       // open connections; more get 503
  int max_connections_per_client = 64;  // open connections per client address; more get 503
  bool healthcheck = false;        // --healthcheck: GET /livez of host:port and exit 0/1
  std::ostream* log = nullptr;     // one JSON line per request; nullptr: no log
  // Test hook: called with each progress record's index (iteration, cell, step, series) as it is produced.
  std::function<void(int)> on_progress;

  int effective_max_streams() const;
};

// Parses argv and the environment. Returns nullopt and fills `message` on --help (exit 0) or on an error
// (exit 2); `help` tells which.
std::optional<ServerOptions> parse_server_options(int argc, const char* const* argv, std::string& message, bool& help);
std::string server_usage();

// The web root to serve: the option if set, else <exe>/../../web, <exe>/../web, <exe>/../share/lienewton/web
// or ./web, whichever holds index.html.
std::string find_web_root(const std::string& configured, const std::string& exe_path);

}  // namespace lienewton::service
