#include "server/api_handlers.hpp"

#include <malloc.h>

#include <algorithm>
#include <cstdio>
#include <set>
#include <stdexcept>

#include "core/basins.hpp"
#include "core/integrate.hpp"
#include "core/solve.hpp"
#include "core/sweep.hpp"
#include "core/work_precision.hpp"
#include "server/http_errors.hpp"
#include "server/http_validators.hpp"
#include "server/output_limits.hpp"
#include "server/query_params.hpp"
#include "server/request_limits.hpp"
#include "server/render_requests.hpp"
#include "server/routes.hpp"
#include "server/static_files.hpp"
#include "render/renderer.hpp"

namespace lienewton::service {

// A work slot: long requests beyond options.effective_max_streams() are refused, so that workers stay free
// for short requests, and beyond max_streams_per_client() from one client address, so that one client cannot
// take every slot.
class ApiHandlers::Slot {
 public:
  Slot(ApiHandlers& owner, std::string client) : owner_(owner), client_(std::move(client)) { owner_.metrics_.work_started(); }
  ~Slot() {
    if (streaming_) owner_.metrics_.stream_finished();
    owner_.metrics_.work_finished();
    bool last = false;
    {
      const std::lock_guard<std::mutex> lock(owner_.slots_mutex_);
      last = --owner_.slots_in_use_ == 0;
      if (--owner_.slots_per_client_[client_] == 0) owner_.slots_per_client_.erase(client_);
    }
    // glibc keeps what a request freed in the arena of the thread that ran it (one per worker thread, up to 8 per
    // core), and hands back only the top of each heap: the memory a large request took stays resident on its
    // worker. The last request to finish returns every arena's free pages, so the idle server is at its floor.
    if (last) malloc_trim(0);
  }
  void mark_streaming() {
    streaming_ = true;
    owner_.metrics_.stream_started();
  }

 private:
  ApiHandlers& owner_;
  std::string client_;
  bool streaming_ = false;
};

namespace {

// Renders may be stored, but are revalidated against their ETag (which changes with the build).
constexpr const char* kRenderCacheControl = "no-cache";

// A GET form carries its request as query parameters; list_fields are array-valued in the JSON request.
json request_json(const HttpRequest& req, const std::set<std::string>& list_fields = {}) {
  return req.method == "POST" ? parse_body(req.body) : query_to_json(req.params, list_fields);
}

// 30 -> "30 s", 2.5 -> "2.5 s".
std::string format_seconds(double seconds) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g s", seconds);
  return buf;
}

HttpResponse json_response(std::string body, int status = 200) {
  HttpResponse res;
  res.status = status;
  res.content_type = "application/json";
  res.body = std::move(body);
  return res;
}

}  // namespace

ApiHandlers::ApiHandlers(const ServerOptions& options, Metrics& metrics, const std::atomic<bool>& draining,
                         const std::atomic<bool>& abort_work)
    : options_(options), metrics_(metrics), draining_(draining), abort_work_(abort_work),
      openapi_document_(openapi_document(options)),
      renderer_(std::make_unique<render::Renderer>(options.render_workers)) {}

ApiHandlers::~ApiHandlers() = default;

std::shared_ptr<ApiHandlers::Slot> ApiHandlers::acquire_slot(const HttpRequest& req) {
  {
    const std::lock_guard<std::mutex> lock(slots_mutex_);
    if (slots_in_use_.load() >= options_.effective_max_streams()) {
      metrics_.rejected("over_capacity");
      throw ApiError(503, "over_capacity", "", "the server is at its limit of concurrent long requests; retry shortly");
    }
    auto found = slots_per_client_.find(req.client);
    if (found != slots_per_client_.end() && found->second >= options_.max_streams_per_client()) {
      metrics_.rejected("client_over_capacity");
      throw ApiError(429, "client_over_capacity", "",
                     "this client already runs " + std::to_string(found->second) +
                         " long requests, its limit; retry when one has finished");
    }
    ++slots_in_use_;
    ++slots_per_client_[req.client];
  }
  return std::make_shared<Slot>(*this, req.client);
}

std::shared_ptr<CancellationToken> ApiHandlers::make_token(double budget_seconds, const HttpRequest& req) {
  const auto timeout = std::chrono::duration_cast<CancellationToken::Clock::duration>(
      std::chrono::duration<double>(budget_seconds));
  return std::make_shared<CancellationToken>(CancellationToken::Clock::now() + timeout, &abort_work_,
                                             disconnects_.watch(req.socket), budget_seconds);
}

// Runs a job with its token as the thread's current one, so that every core loop polls it.
json ApiHandlers::run(const Job& job, const Emit& emit, const CancellationToken& token) const {
  const CancellationScope scope(&token);
  try {
    return job(emit, token);
  } catch (const Cancelled&) {
    throw_stopped(token);
  }
}

void ApiHandlers::progress(int index) const {
  if (options_.on_progress) options_.on_progress(index);
}

void ApiHandlers::throw_stopped(const CancellationToken& token, const std::string& done) const {
  switch (token.reason()) {
    case CancelReason::shutdown:
      throw ApiError(503, "shutting_down", "", "the server is shutting down; the work was cancelled");
    case CancelReason::client_gone:
      throw ApiError(499, "client_gone", "", "the client closed the connection");
    default:
      throw ApiError(504, "deadline_exceeded", "",
                     "the request took longer than the server's limit of " + format_seconds(token.budget_seconds()) +
                         " and was cancelled" + done);
  }
}

// The job of a prepared request: run with the route's hooks (progress, metrics, the stream's records, the token),
// and when it stops early, a 504/499/503 that says how far it got where its items are counted ahead.
ApiHandlers::Job ApiHandlers::job(PreparedRequest request) {
  return [this, request = std::move(request)](const Emit& emit, const CancellationToken& token) {
    std::string unit;
    std::size_t total = 0;
    std::atomic<std::size_t> done{0};
    RunHooks hooks;
    hooks.begin = [&](std::string_view u, std::size_t t) { unit = u, total = t; };
    hooks.step = [&](std::size_t index) {
      progress(static_cast<int>(index));
      ++done;
      return !token.cancelled();
    };
    hooks.record = emit;  // records are made only for a stream
    hooks.solved = [&](Status status, int iterations) {
      metrics_.solve_finished(std::string(to_string(status)), iterations);
    };
    try {
      return run_prepared(request, hooks);
    } catch (const Cancelled&) {
      if (total == 0) throw_stopped(token);
      const std::size_t finished = std::min(done.load(), total);
      throw_stopped(token, ": " + std::to_string(finished) + " of " + std::to_string(total) + " " + unit +
                               " finished, " + std::to_string(total - finished) + " not computed");
    }
  };
}

HttpResponse ApiHandlers::command(const HttpRequest& req) {
  for (const CommandSpec& c : command_table())
    if (req.path == command_path(c.command)) return serve(req, c.command, false);
  throw std::logic_error("no command is routed to " + req.path);
}
HttpResponse ApiHandlers::solve_events(const HttpRequest& req) { return serve(req, Command::solve, true); }
HttpResponse ApiHandlers::render_frames(const HttpRequest& req) { return render(req, request_json(req), service::render_frames, options_.request_timeout); }
// The heatmap's GET form carries a sweep request, whose methods/n/h are lists; absent ones take the defaults
// POST takes (the paper's grid), under the same sweep deadline.
HttpResponse ApiHandlers::render_heatmap(const HttpRequest& req) {
  return render(req, request_json(req, list_fields(fields::sweep | fields::render_heatmap)), service::render_heatmap, options_.sweep_timeout);
}
// The GET form of a basin map: methods, b1 and b2 are lists.
HttpResponse ApiHandlers::render_basins(const HttpRequest& req) {
  return render(req, request_json(req, list_fields(fields::basins | fields::render_basins)), service::render_basins, options_.sweep_timeout);
}
// The GET form carries choices as JSON text: choices=[{"integrator":...,"method":...,"differential":...}].
HttpResponse ApiHandlers::render_work_precision(const HttpRequest& req) {
  return render(req, request_json(req, list_fields(fields::work_precision | fields::render_work_precision)), service::render_work_precision, options_.request_timeout);
}
HttpResponse ApiHandlers::render_invariants(const HttpRequest& req) {
  return render(req, request_json(req, list_fields(fields::integrate | fields::render_invariants)), service::render_invariants, options_.request_timeout);
}
// Motion's GET form: an integration's fields beside a solve's, as on frames.
HttpResponse ApiHandlers::render_motion(const HttpRequest& req) {
  return render(req, request_json(req, list_fields(fields::integrate | fields::render_motion)), service::render_motion, options_.request_timeout);
}
HttpResponse ApiHandlers::render_residuals(const HttpRequest& req) {
  return render(req, request_json(req, list_fields(fields::solve | fields::render_residuals)), service::render_residuals, options_.request_timeout);
}
HttpResponse ApiHandlers::livez(const HttpRequest&) { return json_response(R"({"status":"ok"})"); }
HttpResponse ApiHandlers::version(const HttpRequest&) {
  return json_response(dump(json{{"version", LIENEWTON_VERSION}, {"build", build_id()}}));
}
// Not ready while draining, or while every work slot is taken (a load balancer should send work elsewhere).
HttpResponse ApiHandlers::readyz(const HttpRequest&) {
  if (draining_.load()) return json_response(R"({"status":"draining"})", 503);
  if (slots_in_use_.load() >= options_.effective_max_streams()) return json_response(R"({"status":"saturated"})", 503);
  return json_response(R"({"status":"ok"})");
}
HttpResponse ApiHandlers::metrics(const HttpRequest&) {
  HttpResponse res;
  res.content_type = "text/plain; version=0.0.4";
  res.body = metrics_.render();
  return res;
}
// The document is fixed for the life of the process: the dashboard's reloads revalidate it like a static file.
HttpResponse ApiHandlers::openapi(const HttpRequest& req) {
  static const char* const kCacheControl = "no-cache";
  const std::string etag = content_etag(openapi_document_);
  if (none_match_fails(req, etag, true)) return not_modified(etag, kCacheControl);
  HttpResponse res = json_response(openapi_document_);
  res.set_header("ETag", etag);
  res.set_header("Cache-Control", kCacheControl);
  return res;
}
HttpResponse ApiHandlers::static_file(const HttpRequest& req) { return serve_static(options_.web_root, req); }

HttpResponse ApiHandlers::serve(const HttpRequest& req, Command command, bool sse) {
  // Asked for Server-Sent Events alone, a POST route has nothing it may send: it answers JSON or NDJSON.
  const std::string& accept = req.header("Accept");
  const bool ndjson = accept_quality(accept, "application/x-ndjson", true) > 0;
  if (!sse && accept_quality(accept, "text/event-stream", true) > 0 && accept_quality(accept, "application/json") == 0 &&
      accept_quality(accept, "application/x-ndjson") == 0)
    throw ApiError(406, "not_acceptable", "",
                   "this route answers application/json, or streams application/x-ndjson; Server-Sent Events are "
                   "GET /api/v1/solve/events");
  const json body = request_json(req);  // parsing only: no compiling, no evaluating before the gate
  auto slot = acquire_slot(req);
  const bool is_map = command_spec(command).is_map;
  const auto token = make_token(is_map ? options_.sweep_timeout : options_.request_timeout, req);
  // Preparing the request validates it, which compiles and evaluates a user's program: under the slot and the
  // token, yet before a stream's status line, so that its refusals stay plain 400/422 answers.
  Job job;
  {
    const CancellationScope scope(token.get());
    try {
      PreparedRequest request = prepare_request(command, body, options_.limits);
      apply_output_limits(request, options_.output);
      job = this->job(std::move(request));
    } catch (const Cancelled&) {
      throw_stopped(*token);
    }
  }
  if (sse || ndjson) return stream(std::move(slot), std::move(job), sse, token);
  return json_response(dump(run(job, Emit{}, *token)));
}

// Streams run inside the body stream, on the connection's own worker: each record is written as it is
// produced, and a failed write (client gone) cancels the work at the next callback. The stream owns the work
// slot, so the slot is held until the transport drops the response.
HttpResponse ApiHandlers::stream(std::shared_ptr<Slot> slot, Job job, bool sse, std::shared_ptr<CancellationToken> token) {
  slot->mark_streaming();
  HttpResponse res;
  res.set_header("Cache-Control", "no-store");
  res.set_header("X-Accel-Buffering", "no");
  // Only application/x-ndjson and text/event-stream: the Debian build compresses (and buffers) other types.
  res.content_type = sse ? "text/event-stream" : "application/x-ndjson";
  res.stream = [this, slot, job = std::move(job), token, sse, metrics = &metrics_](const ChunkSink& sink) {
    auto write = [&](std::string_view kind, json record) {
      const std::string line = stream_line(kind, record);
      const std::string text = sse ? "event: " + std::string(kind) + "\ndata: " + line + "\n\n" : line + "\n";
      if (!sink(text)) {
        token->cancel(CancelReason::client_gone);
        return false;
      }
      return true;
    };
    json terminal;
    const char* kind = "result";
    try {
      terminal = run(job, write, *token);
    } catch (const ApiError& e) {
      kind = "error";
      terminal = error_body(e.code(), e.field(), e.what());
    } catch (const RequestError& e) {
      kind = "error";
      terminal = error_body(e);
    } catch (...) {
      // Nothing may escape a body stream: it runs outside the transport's exception handler.
      log_internal_error("a body stream", std::current_exception());
      kind = "error";
      terminal = error_body("internal_error", "", "internal error");
    }
    // The status line (200) went out with the first record: the metrics count how the stream ended.
    metrics->stream_ended(kind == std::string("result") ? "result" : terminal["error"].value("code", "error"));
    return token->reason() != CancelReason::client_gone && write(kind, std::move(terminal));
  };
  return res;
}

namespace {
// The picture's media type, read from its first bytes: each route's format field has been checked by its drawing.
const char* image_type(const std::vector<unsigned char>& picture) {
  const std::string_view head(reinterpret_cast<const char*>(picture.data()), std::min<std::size_t>(picture.size(), 12));
  if (head.size() == 12 && head.substr(0, 4) == "RIFF" && head.substr(8, 4) == "WEBP") return "image/webp";
  if (head.substr(0, 4) == "\x89PNG") return "image/png";
  return "image/svg+xml";
}
}  // namespace

HttpResponse ApiHandlers::render(const HttpRequest& req, const json& body, RenderRequestFn draw,
                                 double budget_seconds) {
  check_image_pixels(body, options_.output);
  // A GET render is a pure function of the route, the canonical request (keys sorted) and the build, so its tag
  // is known before drawing: a repeated GET costs a hash, not a render. POST renders stay uncached.
  const bool cacheable = req.method == "GET";
  const std::string etag = cacheable ? content_etag(build_id() + " " + req.path + " " + dump(body)) : "";
  if (cacheable && none_match_fails(req, etag, false)) return not_modified(etag, kRenderCacheControl);
  // The slot before anything costly is parsed (a parameter's expression, a finished sweep), as on the JSON routes.
  const std::shared_ptr<Slot> slot = acquire_slot(req);
  const auto token_ptr = make_token(budget_seconds, req);
  const CancellationToken& token = *token_ptr;
  const CancellationScope scope(&token);
  RenderHooks hooks;
  hooks.output = options_.output;
  hooks.keep_going = [&](int index) {
    progress(index);
    return !token.cancelled();
  };
  hooks.on_cell = [&](const SweepCell& c) { metrics_.solve_finished(std::string(to_string(c.status)), c.iterations); };
  hooks.on_solve = [&](const SolveResult& r) { metrics_.solve_finished(std::string(to_string(r.status)), r.iterations); };
  // What a picture cannot say: the drawn integration's warnings (codes, each once), as a header.
  std::vector<std::string> warnings;
  hooks.on_integration = [&](const IntegrateResult& r) {
    for (const IntegrateWarning& w : r.warnings)
      if (std::find(warnings.begin(), warnings.end(), w.code) == warnings.end()) warnings.push_back(w.code);
  };
  std::vector<unsigned char> picture;
  try {
    picture = draw(body, options_.limits, *renderer_, hooks);
  } catch (const RenderCancelled&) {
    throw_stopped(token);
  } catch (const Cancelled&) {
    throw_stopped(token);
  } catch (const render::RenderUnavailable&) {
    throw ApiError(503, "render_unavailable", "", "the offscreen renderer is unavailable; everything else still works");
  }
  HttpResponse res;
  res.set_header("Cache-Control", cacheable ? kRenderCacheControl : "no-store");
  if (cacheable) res.set_header("ETag", etag);
  if (!warnings.empty()) {
    std::string codes;
    for (const std::string& code : warnings) codes += (codes.empty() ? "" : ", ") + code;
    res.set_header(kWarningsHeader, codes);
  }
  res.content_type = image_type(picture);
  res.body.assign(picture.begin(), picture.end());
  return res;
}

}  // namespace lienewton::service
