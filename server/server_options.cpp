#include "server/server_options.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string_view>

namespace lienewton::service {
namespace {

struct Flag {
  const char* name;
  const char* env;
  const char* help;
};

constexpr Flag kFlags[] = {
    {"--host", "LIENEWTON_HOST", "address to bind (default 127.0.0.1; the container uses 0.0.0.0)"},
    {"--port", "LIENEWTON_PORT", "TCP port (default 8080)"},
    {"--threads", "LIENEWTON_THREADS", "workers; each serves one connection from accept to close (default 64)"},
    {"--max-n", "LIENEWTON_MAX_N", "largest matrix size N accepted (default 64)"},
    {"--max-iterations", "LIENEWTON_MAX_ITERATIONS", "largest max_iterations accepted (default 10000)"},
    {"--max-grid", "LIENEWTON_MAX_GRID", "largest sweep grid (methods x n x h cells) accepted (default 5000)"},
    {"--max-t-end", "LIENEWTON_MAX_T_END", "longest t_end of integrate and work-precision accepted (default 100)"},
    {"--request-timeout", "LIENEWTON_REQUEST_TIMEOUT", "seconds a request (or stream) may run; then 504 (default 30)"},
    {"--sweep-timeout", "LIENEWTON_SWEEP_TIMEOUT", "seconds a sweep or heatmap render (JSON or stream) may run; then 504 (default 120)"},
    {"--web-root", "LIENEWTON_WEB_ROOT", "directory of the dashboard (default: the repository's web/ next to the binary, or ./web)"},
    {"--max-body", "LIENEWTON_MAX_BODY", "largest request body in bytes; larger gets 413 (default 1048576)"},
    {"--max-streams", "LIENEWTON_MAX_STREAMS", "concurrent long requests (streams, solves, sweeps, renders); more get 503; one client address may run half of them, more get 429 (default 6, at most threads - 2)"},
    {"--render-workers", "LIENEWTON_RENDER_WORKERS", "offscreen GL contexts for PNG renders (default 1)"},
    {"--read-timeout", "LIENEWTON_READ_TIMEOUT", "seconds any one read or write on a connection may stall; then it is closed (default 5)"},
    {"--max-connections", "LIENEWTON_MAX_CONNECTIONS", "connections held at once; more wait in the listen backlog (default 512, at most 900)"},
    {"--max-queued", "LIENEWTON_MAX_QUEUED", "connections waiting for a worker; more are answered 503 (default 4 x threads)"},
    {"--trusted-front", "LIENEWTON_TRUSTED_FRONT", "comma-separated addresses of the front (nginx) whose X-Real-IP names the client (default: none)"},
    {"--max-output-values", "LIENEWTON_MAX_OUTPUT_VALUES", "most numbers one result may hold (iterates x N^2, frames, steps, cells); more get 413 (default 1000000)"},
    {"--max-image-pixels", "LIENEWTON_MAX_IMAGE_PIXELS", "largest width x height of a PNG render; larger gets 413 (default 4194304)"},
    {"--shutdown-grace", "LIENEWTON_SHUTDOWN_GRACE", "seconds open streams may finish after SIGTERM before they are ended with an error record (default 3)"},
};

bool parse_int(std::string_view text, long long lo, long long hi, int& out) {
  long long v = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || v < lo || v > hi) return false;
  out = static_cast<int>(v);
  return true;
}

bool parse_double(const std::string& text, double lo, double hi, double& out) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v) || v < lo || v > hi) return false;
  out = v;
  return true;
}

// Applies one setting; returns an error message or "".
std::string apply(ServerOptions& o, std::string_view name, const std::string& value) {
  int i = 0;
  double d = 0;
  auto bad = [&](const char* what) { return std::string(name) + " must be " + what; };
  if (name == "--host") {
    if (value.empty()) return bad("a host name or address");
    o.host = value;
  } else if (name == "--port") {
    if (!parse_int(value, 0, 65535, o.port)) return bad("an integer in [0, 65535]");
  } else if (name == "--threads") {
    if (!parse_int(value, 3, 1024, o.threads)) return bad("an integer in [3, 1024]");
  } else if (name == "--max-n") {
    if (!parse_int(value, 2, 100000, o.limits.max_n)) return bad("an integer in [2, 100000]");
  } else if (name == "--max-iterations") {
    if (!parse_int(value, 1, 100000000, o.limits.max_iterations)) return bad("an integer in [1, 1e8]");
  } else if (name == "--max-grid") {
    if (!parse_int(value, 1, 100000000, i)) return bad("an integer in [1, 1e8]");
    o.limits.max_grid_cells = static_cast<std::size_t>(i);
  } else if (name == "--max-t-end") {
    if (!parse_double(value, 0.001, fields::t_end.max, o.limits.max_t_end)) return bad("a number in [0.001, 1e9]");
  } else if (name == "--request-timeout") {
    if (!parse_double(value, 0.001, 86400, o.request_timeout)) return bad("a number of seconds in [0.001, 86400]");
  } else if (name == "--sweep-timeout") {
    if (!parse_double(value, 0.001, 86400, o.sweep_timeout)) return bad("a number of seconds in [0.001, 86400]");
  } else if (name == "--web-root") {
    o.web_root = value;
  } else if (name == "--max-body") {
    if (!parse_int(value, 1, 1 << 30, i)) return bad("an integer number of bytes in [1, 2^30]");
    o.max_body = static_cast<std::size_t>(i);
  } else if (name == "--max-streams") {
    if (!parse_int(value, 1, 1024, o.max_streams)) return bad("an integer in [1, 1024]");
  } else if (name == "--render-workers") {
    if (!parse_int(value, 1, 64, o.render_workers)) return bad("an integer in [1, 64]");
  } else if (name == "--read-timeout") {
    if (!parse_double(value, 0.1, 3600, o.read_timeout)) return bad("a number of seconds in [0.1, 3600]");
  } else if (name == "--max-connections") {
    // cpp-httplib 0.11.4 (select-based) answers 500 for descriptors >= FD_SETSIZE (1024).
    if (!parse_int(value, 4, 900, o.max_connections)) return bad("an integer in [4, 900]");
  } else if (name == "--max-queued") {
    if (!parse_int(value, 1, 100000, o.max_queued)) return bad("an integer in [1, 100000]");
  } else if (name == "--trusted-front") {
    o.trusted_fronts.clear();
    for (std::size_t start = 0; start <= value.size();) {
      const std::size_t comma = std::min(value.find(',', start), value.size());
      if (comma > start) o.trusted_fronts.push_back(value.substr(start, comma - start));
      start = comma + 1;
    }
    if (o.trusted_fronts.empty()) return bad("a comma-separated list of addresses");
  } else if (name == "--max-output-values") {
    if (!parse_int(value, 1000, 1 << 30, i)) return bad("an integer in [1000, 2^30]");
    o.output.max_values = static_cast<std::size_t>(i);
  } else if (name == "--max-image-pixels") {
    if (!parse_int(value, 4096, 1 << 26, i)) return bad("an integer in [4096, 2^26]");
    o.output.max_image_pixels = static_cast<std::size_t>(i);
  } else if (name == "--shutdown-grace") {
    if (!parse_double(value, 0, 8, d)) return bad("a number of seconds in [0, 8]");
    o.shutdown_grace = d;
  } else {
    return "unknown option " + std::string(name) + " (see --help)";
  }
  return "";
}

}  // namespace

int ServerOptions::effective_max_streams() const {
  // Two workers at least stay free for short requests (/livez, /metrics, static files).
  return std::max(1, std::min(max_streams, threads - 2));
}

int ServerOptions::max_streams_per_client() const { return std::max(1, effective_max_streams() / 2); }

std::string server_usage() {
  std::string s =
      "usage: lienewton-server [options]\n"
      "Serves the lienewton JSON API, its NDJSON/SSE streams, PNG renders, /livez, /readyz, /metrics,\n"
      "/openapi.json and the dashboard. Every option can also be set by the environment variable shown.\n\n";
  for (const auto& f : kFlags) {
    s += "  " + std::string(f.name) + " VALUE";
    s += std::string(f.name).size() < 18 ? std::string(18 - std::string(f.name).size(), ' ') : " ";
    s += std::string(f.env) + "\n      " + f.help + "\n";
  }
  s += "  --healthcheck           GET /livez on the configured host and port; exit 0 when it answers 200, else 1\n"
       "  --help                  this text\n"
       "SIGTERM/SIGINT: /readyz turns 503, new work is refused, open streams get --shutdown-grace seconds and then\n"
       "a terminal error record, and the process exits 0 within 10 s.\n";
  return s;
}

std::optional<ServerOptions> parse_server_options(int argc, const char* const* argv, std::string& message, bool& help) {
  ServerOptions o;
  help = false;
  for (const auto& f : kFlags) {
    if (const char* v = std::getenv(f.env)) {
      if (auto err = apply(o, f.name, v); !err.empty()) {
        message = std::string(f.env) + ": " + err;
        return std::nullopt;
      }
    }
  }
  for (int k = 1; k < argc; ++k) {
    std::string arg = argv[k];
    if (arg == "--help" || arg == "-h") {
      help = true;
      message = server_usage();
      return std::nullopt;
    }
    if (arg == "--healthcheck") {
      o.healthcheck = true;
      continue;
    }
    std::string value;
    if (auto eq = arg.find('='); eq != std::string::npos) {
      value = arg.substr(eq + 1);
      arg = arg.substr(0, eq);
    } else if (k + 1 < argc) {
      value = argv[++k];
    } else {
      message = arg + " needs a value (see --help)";
      return std::nullopt;
    }
    if (auto err = apply(o, arg, value); !err.empty()) {
      message = err;
      return std::nullopt;
    }
  }
  return o;
}

std::string find_web_root(const std::string& configured, const std::string& exe_path) {
  namespace fs = std::filesystem;
  if (!configured.empty()) return configured;
  std::error_code ec;
  const fs::path exe_dir = fs::weakly_canonical(fs::path(exe_path), ec).parent_path();
  const fs::path candidates[] = {exe_dir / ".." / ".." / "web", exe_dir / ".." / "web",
                                 exe_dir / ".." / "share" / "lienewton" / "web", fs::current_path(ec) / "web"};
  for (const auto& c : candidates) {
    if (fs::is_regular_file(c / "index.html", ec)) return fs::weakly_canonical(c, ec).string();
  }
  return (fs::current_path(ec) / "web").string();
}

}  // namespace lienewton::service
