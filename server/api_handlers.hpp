#pragma once
// Handlers of the long-work routes (solve, sweep, integrate, work-precision, renders): parse and validate,
// take a work slot, then run inline (JSON, PNG) or inside a chunked provider (NDJSON, SSE).
#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "server/cancellation.hpp"
#include "server/json_codec.hpp"
#include "server/metrics.hpp"
#include "server/routes.hpp"
#include "server/server_options.hpp"

namespace lienewton::render { class Renderer; }

namespace httplib {
struct Request;
struct Response;
}  // namespace httplib

namespace lienewton::service {

class ApiHandlers {
 public:
  ApiHandlers(const ServerOptions& options, Metrics& metrics, const std::atomic<bool>& abort_work);
  ~ApiHandlers();
  void handle(const RouteSpec& route, const httplib::Request& req, httplib::Response& res);

  // Writes one progress record; false when the client has gone.
  using Emit = std::function<bool(const char* type, json record)>;
  // Runs the work; returns the terminal result (without "type"). Throws ApiError/RequestError.
  using Job = std::function<json(const Emit& emit, StopCheck& stop)>;

 private:
  class Slot;
  std::shared_ptr<Slot> acquire_slot();
  StopCheck make_stop() const;
  void progress(int index) const;
  [[noreturn]] void throw_stopped(const StopCheck& stop) const;
  json body_json(const RouteSpec& route, const httplib::Request& req) const;

  Job solve_job(const json& body);
  Job sweep_job(const json& body);
  Job integrate_job(const json& body);
  Job work_precision_job(const json& body);
  void serve(const httplib::Request& req, httplib::Response& res, Job job, bool sse);
  void stream(httplib::Response& res, std::shared_ptr<Slot> slot, Job job, bool sse);
  void render(const RouteSpec& route, const json& body, httplib::Response& res);

  const ServerOptions& options_;
  Metrics& metrics_;
  const std::atomic<bool>& abort_work_;
  std::atomic<int> slots_in_use_{0};
  std::unique_ptr<render::Renderer> renderer_;
};

}  // namespace lienewton::service
