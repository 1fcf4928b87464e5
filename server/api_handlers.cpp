#include "server/api_handlers.hpp"

#include "server/httplib_include.hpp"

#include "core/integrate.hpp"
#include "core/solve.hpp"
#include "core/sweep.hpp"
#include "core/work_precision.hpp"
#include "server/http_errors.hpp"
#include "server/query_params.hpp"
#include "server/render_requests.hpp"
#include "render/renderer.hpp"

namespace lienewton::service {

// A work slot: long requests beyond options.effective_max_streams() are refused, so that workers stay free
// for /livez and the queue of cpp-httplib (unbounded) never fills with solves.
class ApiHandlers::Slot {
 public:
  Slot(std::atomic<int>& in_use, Metrics& metrics) : in_use_(in_use), metrics_(metrics) { metrics_.work_started(); }
  ~Slot() {
    if (streaming_) metrics_.stream_finished();
    metrics_.work_finished();
    --in_use_;
  }
  void mark_streaming() {
    streaming_ = true;
    metrics_.stream_started();
  }

 private:
  std::atomic<int>& in_use_;
  Metrics& metrics_;
  bool streaming_ = false;
};

ApiHandlers::ApiHandlers(const ServerOptions& options, Metrics& metrics, const std::atomic<bool>& abort_work)
    : options_(options), metrics_(metrics), abort_work_(abort_work),
      renderer_(std::make_unique<render::Renderer>(options.render_workers)) {}

ApiHandlers::~ApiHandlers() = default;

std::shared_ptr<ApiHandlers::Slot> ApiHandlers::acquire_slot() {
  int current = slots_in_use_.load();
  do {
    if (current >= options_.effective_max_streams()) {
      metrics_.rejected("over_capacity");
      throw ApiError(503, "over_capacity", "", "the server is at its limit of concurrent long requests; retry shortly");
    }
  } while (!slots_in_use_.compare_exchange_weak(current, current + 1));
  return std::make_shared<Slot>(slots_in_use_, metrics_);
}

StopCheck ApiHandlers::make_stop() const {
  const auto timeout = std::chrono::duration_cast<StopCheck::Clock::duration>(
      std::chrono::duration<double>(options_.request_timeout));
  return StopCheck(StopCheck::Clock::now() + timeout, abort_work_);
}

void ApiHandlers::progress(int index) const {
  if (options_.on_progress) options_.on_progress(index);
}

void ApiHandlers::throw_stopped(const StopCheck& stop) const {
  switch (stop.reason()) {
    case StopReason::shutdown:
      throw ApiError(503, "shutting_down", "", "the server is shutting down; the work was cancelled");
    case StopReason::client_gone:
      throw ApiError(499, "client_gone", "", "the client closed the connection");
    default:
      throw ApiError(504, "deadline_exceeded", "",
                     "the request took longer than the server's limit of " +
                         std::to_string(options_.request_timeout) + " s and was cancelled");
  }
}

json ApiHandlers::body_json(const RouteSpec& route, const httplib::Request& req) const {
  if (route.method == "GET") {
    // The heatmap's GET form carries a sweep request, whose methods/n/h are lists.
    if (route.id == RouteId::render_heatmap_get) return query_to_json(req.params, {"methods", "n", "h"});
    return query_to_json(req.params);
  }
  return parse_body(req.body);
}

ApiHandlers::Job ApiHandlers::solve_job(const json& body) {
  SolveRequest request = solve_request_from_json(body, options_.limits);
  validate(request);
  return [this, request](const Emit& emit, StopCheck& stop) {
    SolveResult result = solve(request, [&](const TraceRecord& t) {
      progress(t.iteration);
      if (emit && !emit("iteration", to_json(t, request.include_iterates))) return false;
      return !stop.should_stop();
    });
    metrics_.solve_finished(std::string(to_string(result.status)), result.iterations);
    if (result.status == Status::cancelled) throw_stopped(stop);
    return to_json(result, request.include_iterates);
  };
}

ApiHandlers::Job ApiHandlers::sweep_job(const json& body) {
  SweepRequest request = sweep_request_from_json(body, options_.limits);
  validate(request);
  return [this, request](const Emit& emit, StopCheck& stop) {
    int index = 0;
    bool stopped = false;
    SweepResult result = sweep(request, [&](const SweepCell& cell) {
      progress(index++);
      metrics_.solve_finished(std::string(to_string(cell.status)), cell.iterations);
      if (emit && !emit("cell", to_json(cell))) return !(stopped = true);
      return !(stopped = stop.should_stop());
    });
    if (stopped) throw_stopped(stop);
    return to_json(result);
  };
}

ApiHandlers::Job ApiHandlers::integrate_job(const json& body) {
  IntegrateRequest request = integrate_request_from_json(body, options_.limits);
  validate(request);
  return [this, request](const Emit& emit, StopCheck& stop) {
    bool stopped = false;
    IntegrateResult result = integrate(request, [&](const StepRecord& step) {
      progress(step.step);
      if (emit && !emit("step", to_json(step))) return !(stopped = true);
      return !(stopped = stop.should_stop());
    });
    if (stopped || result.status == Status::cancelled) {
      if (stop.reason() != StopReason::none) throw_stopped(stop);
    }
    return to_json(result);
  };
}

ApiHandlers::Job ApiHandlers::work_precision_job(const json& body) {
  WorkPrecisionRequest request = work_precision_request_from_json(body, options_.limits);
  validate(request);
  return [this, request](const Emit& emit, StopCheck& stop) {
    int index = 0;
    bool stopped = false;
    WorkPrecisionResult result = work_precision(request, [&](const WorkPrecisionSeries& series) {
      progress(index++);
      if (emit && !emit("series", to_json(series))) return !(stopped = true);
      return !(stopped = stop.should_stop());
    });
    if (stopped) throw_stopped(stop);
    return to_json(result);
  };
}

void ApiHandlers::handle(const RouteSpec& route, const httplib::Request& req, httplib::Response& res) {
  try {
    const json body = body_json(route, req);
    switch (route.id) {
      case RouteId::solve: return serve(req, res, solve_job(body), false);
      case RouteId::solve_events: return serve(req, res, solve_job(body), true);
      case RouteId::sweep: return serve(req, res, sweep_job(body), false);
      case RouteId::integrate: return serve(req, res, integrate_job(body), false);
      case RouteId::work_precision: return serve(req, res, work_precision_job(body), false);
      default: return render(route, body, res);
    }
  } catch (const ApiError& e) {
    if (e.status() == 503) res.set_header("Retry-After", "1");
    send_error(res, e.status(), e.code(), e.field(), e.what());
  } catch (const RequestError& e) {
    const int status = e.kind() == RequestError::Kind::unprocessable ? 422 : 400;
    send_error(res, status, error_code(e), e.field(), e.what());
  }
}

void ApiHandlers::serve(const httplib::Request& req, httplib::Response& res, Job job, bool sse) {
  auto slot = acquire_slot();
  const bool ndjson = req.get_header_value("Accept").find("application/x-ndjson") != std::string::npos;
  if (sse || ndjson) return stream(res, std::move(slot), std::move(job), sse);
  StopCheck stop = make_stop();
  const json result = job(Emit{}, stop);
  res.status = 200;
  res.set_content(dump(result), "application/json");
}

// Streams run inside the chunked provider, on the connection's own worker: each record is written as it is
// produced, and a failed write (client gone) cancels the work at the next callback.
void ApiHandlers::stream(httplib::Response& res, std::shared_ptr<Slot> slot, Job job, bool sse) {
  slot->mark_streaming();
  res.status = 200;
  res.set_header("Cache-Control", "no-store");
  res.set_header("X-Accel-Buffering", "no");
  auto stop = std::make_shared<StopCheck>(make_stop());
  // Only application/x-ndjson and text/event-stream: the Debian build compresses (and buffers) other types.
  const char* type = sse ? "text/event-stream" : "application/x-ndjson";
  res.set_chunked_content_provider(type, [slot, job = std::move(job), stop, sse](std::size_t, httplib::DataSink& sink) {
    auto write = [&](const char* kind, json record) {
      // "type" first, for people reading the stream; the rest keeps the result's field order.
      std::string line = dump(record);
      line = std::string("{\"type\":\"") + kind + "\"" + (line.size() > 2 ? "," : "") + line.substr(1);
      const std::string text = sse ? "event: " + std::string(kind) + "\ndata: " + line + "\n\n" : line + "\n";
      if (!sink.write(text.data(), text.size())) {
        stop->client_gone();
        return false;
      }
      return true;
    };
    json terminal;
    const char* kind = "result";
    try {
      terminal = job(write, *stop);
    } catch (const ApiError& e) {
      kind = "error";
      terminal = error_body(e.code(), e.field(), e.what());
    } catch (const RequestError& e) {
      kind = "error";
      terminal = error_body(e);
    } catch (...) {
      // Nothing may escape a content provider: it runs outside cpp-httplib's exception handler.
      kind = "error";
      terminal = error_body("internal_error", "", "internal error");
    }
    if (stop->reason() == StopReason::client_gone || !write(kind, std::move(terminal))) return false;
    sink.done();
    return true;
  });
}

void ApiHandlers::render(const RouteSpec& route, const json& body, httplib::Response& res) {
  StopCheck stop = make_stop();
  std::shared_ptr<Slot> slot;
  RenderHooks hooks;
  hooks.before_work = [&] { slot = acquire_slot(); };
  hooks.keep_going = [&](int index) {
    progress(index);
    return !stop.should_stop();
  };
  hooks.on_cell = [&](const SweepCell& c) { metrics_.solve_finished(std::string(to_string(c.status)), c.iterations); };
  hooks.on_solve = [&](const SolveResult& r) { metrics_.solve_finished(std::string(to_string(r.status)), r.iterations); };
  std::vector<unsigned char> png;
  try {
    const bool frames = route.id == RouteId::render_frames_post || route.id == RouteId::render_frames_get;
    png = frames ? render_frames(body, options_.limits, *renderer_, hooks)
                 : render_heatmap(body, options_.limits, *renderer_, hooks);
  } catch (const RenderCancelled&) {
    throw_stopped(stop);
  } catch (const render::RenderUnavailable&) {
    throw ApiError(503, "render_unavailable", "", "the offscreen renderer is unavailable; everything else still works");
  }
  res.status = 200;
  res.set_header("Cache-Control", "no-store");
  res.set_content(reinterpret_cast<const char*>(png.data()), png.size(), "image/png");
}

void send_error(httplib::Response& res, int status, std::string_view code, std::string_view field,
                std::string_view message) {
  res.status = status;
  res.set_content(dump(error_body(code, field, message)), "application/json");
}

}  // namespace lienewton::service
