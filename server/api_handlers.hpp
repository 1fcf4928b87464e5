#pragma once
// The service's handlers, one per route: each turns an HttpRequest into an HttpResponse (or a record stream) and
// never sees the transport. Long-work routes (solve, sweep, integrate, work-precision, renders) parse, take a
// work slot and a cancellation token (deadline, shutdown, client gone), and only then validate (which compiles
// and evaluates a user's program), then run inline (JSON, PNG) or inside the response's body stream (NDJSON, SSE).
#include <atomic>
#include <functional>
#include <map>
#include <mutex>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/cancellation.hpp"
#include "server/disconnect_watch.hpp"
#include "server/http_exchange.hpp"
#include "server/json_codec.hpp"
#include "server/metrics.hpp"
#include "server/render_requests.hpp"
#include "server/request_runner.hpp"
#include "server/server_options.hpp"

namespace lienewton::render { class Renderer; }

namespace lienewton::service {

class ApiHandlers {
 public:
  // draining: /readyz answers 503 while set; abort_work: cancels long work in progress.
  ApiHandlers(const ServerOptions& options, Metrics& metrics, const std::atomic<bool>& draining,
              const std::atomic<bool>& abort_work);
  ~ApiHandlers();

  // POST /api/v1/<command>: every compute command of command_table(), by the request's path.
  HttpResponse command(const HttpRequest& req);
  HttpResponse solve_events(const HttpRequest& req);
  HttpResponse render_frames(const HttpRequest& req);
  HttpResponse render_heatmap(const HttpRequest& req);
  HttpResponse render_basins(const HttpRequest& req);
  HttpResponse render_work_precision(const HttpRequest& req);
  HttpResponse render_invariants(const HttpRequest& req);
  HttpResponse render_motion(const HttpRequest& req);
  HttpResponse render_residuals(const HttpRequest& req);
  HttpResponse livez(const HttpRequest& req);
  HttpResponse version(const HttpRequest& req);
  HttpResponse readyz(const HttpRequest& req);
  HttpResponse metrics(const HttpRequest& req);
  HttpResponse openapi(const HttpRequest& req);
  HttpResponse static_file(const HttpRequest& req);

  // Writes one progress record; false when the client has gone.
  using Emit = std::function<bool(std::string_view type, json record)>;
  // Runs the work; returns the terminal result (without "type"). Throws ApiError/RequestError.
  using Job = std::function<json(const Emit& emit, const CancellationToken& token)>;

 private:
  class Slot;
  std::shared_ptr<Slot> acquire_slot(const HttpRequest& req);
  // budget_seconds: the deadline (--request-timeout, or --sweep-timeout for sweeps and heatmaps); the token is
  // also cancelled when the client of the request's socket leaves.
  std::shared_ptr<CancellationToken> make_token(double budget_seconds, const HttpRequest& req);
  json run(const Job& job, const Emit& emit, const CancellationToken& token) const;
  void progress(int index) const;
  // done: what the work got through before it stopped, appended to the deadline message.
  [[noreturn]] void throw_stopped(const CancellationToken& token, const std::string& done = {}) const;

  Job job(PreparedRequest request);
  HttpResponse serve(const HttpRequest& req, Command command, bool sse);
  HttpResponse stream(std::shared_ptr<Slot> slot, Job job, bool sse, std::shared_ptr<CancellationToken> token);
  HttpResponse render(const HttpRequest& req, const json& body, RenderRequestFn draw, double budget_seconds);

  const ServerOptions& options_;
  Metrics& metrics_;
  const std::atomic<bool>& draining_;
  const std::atomic<bool>& abort_work_;
  const std::string openapi_document_;
  std::atomic<int> slots_in_use_{0};
  std::mutex slots_mutex_;
  std::map<std::string, int> slots_per_client_;  // long requests running per client address
  std::unique_ptr<render::Renderer> renderer_;
  DisconnectWatch disconnects_;
};

}  // namespace lienewton::service
