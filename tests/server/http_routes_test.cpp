// Every route answers in the documented format.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "server/json_codec.hpp"
#include "test_server.hpp"

namespace lienewton::service {
namespace {


const std::string kSolve =
    R"({"problem":"paper-linear","n":3,"h":0.5,"method":"newton-group","differential":"exact","seed":1})";

bool is_png(const std::string& body) { return body.size() > 8 && body.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0; }

// An SVG's words: its <text> elements' contents joined by spaces, so that a title wrapped onto several lines of a
// narrow picture reads as one.
std::string svg_words(const std::string& svg) {
  std::string words;
  for (std::size_t at = svg.find("<text"); at != std::string::npos; at = svg.find("<text", at + 1)) {
    const std::size_t begin = svg.find('>', at) + 1;
    words.append(words.empty() ? "" : " ").append(svg, begin, svg.find("</text>", begin) - begin);
  }
  return words;
}

class Routes : public testing::SharedServerTest {};

TEST_F(Routes, HealthMetricsAndOpenApi) {
  auto c = client();
  auto live = c.Get("/livez");
  ASSERT_TRUE(live);
  EXPECT_EQ(live->status, 200);
  EXPECT_EQ(json::parse(live->body)["status"], "ok");
  EXPECT_EQ(live->get_header_value("X-Content-Type-Options"), "nosniff");
  auto ready = c.Get("/readyz");
  ASSERT_TRUE(ready);
  EXPECT_EQ(ready->status, 200);
  // The request counter is written by the server's logger after the answer has gone out, so a /metrics sent at
  // once can arrive before it: ask again (a few times at most) until /livez is counted.
  auto metrics = c.Get("/metrics");
  for (int i = 0; i < 50 && metrics && metrics->body.find("route=\"/livez\"") == std::string::npos; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    metrics = c.Get("/metrics");
  }
  ASSERT_TRUE(metrics);
  EXPECT_EQ(metrics->status, 200);
  EXPECT_NE(metrics->body.find("lienewton_http_requests_total{route=\"/livez\""), std::string::npos);
  EXPECT_NE(metrics->body.find("lienewton_streams_in_flight"), std::string::npos);
  EXPECT_NE(metrics->body.find("lienewton_solve_iterations_bucket"), std::string::npos);
  auto doc = c.Get("/openapi.json");
  ASSERT_TRUE(doc);
  EXPECT_EQ(json::parse(doc->body)["openapi"], "3.0.3");
}

TEST_F(Routes, SolveAnswersTheDocumentedFormat) {
  auto c = client();
  auto res = c.Post("/api/v1/solve", kSolve, "application/json");
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200) << res->body;
  EXPECT_EQ(res->get_header_value("Content-Type"), "application/json");
  const json r = json::parse(res->body);
  EXPECT_EQ(r["status"], "converged");
  for (const char* field : {"status", "reason", "iterations", "rate", "residual", "orthogonality_error", "y", "trace",
                            "seconds", "cpu_seconds", "linear_solver"}) {
    EXPECT_TRUE(r.contains(field)) << field;
  }
  EXPECT_EQ(r["y"].size(), 3u);
  const json& t = r["trace"][0];
  for (const char* field : {"iteration", "residual", "step", "angle", "distance_to_pi", "orthogonality_error", "seconds",
                            "cpu_seconds"}) {
    EXPECT_TRUE(t.contains(field)) << field;
  }
  EXPECT_FALSE(t.contains("y"));
  // curl -d sends application/x-www-form-urlencoded; the README's curl line must work.
  auto form = c.Post("/api/v1/solve", kSolve, "application/x-www-form-urlencoded");
  ASSERT_TRUE(form);
  EXPECT_EQ(form->status, 200);
}

// "stopping" reaches the solver: the case paper-linear, N = 5, h = 16, Version 2 with
// dexpinv-1, where v_n leaves log's principal branch, so ||f~(v_n)|| falls below tol = 0.5 while ||f(y_n)||
// stays near 2 pi. Section 5's rule runs to the cap; the algebra-residual rule stops on ||f~||.
TEST_F(Routes, StoppingSelectsVersion2sRule) {
  auto c = client();
  auto solve = [&](const char* stopping) {
    const std::string body = R"({"problem":"paper-linear","n":5,"h":16,"method":"newton-algebra",)"
                             R"("differential":"dexpinv-1","tol":0.5,"stopping":")" + std::string(stopping) + "\"}";
    auto res = c.Post("/api/v1/solve", body, "application/json");
    EXPECT_TRUE(res && res->status == 200) << (res ? res->body : "no answer");
    return res ? json::parse(res->body) : json();
  };
  const json by_f = solve("residual"), by_algebra = solve("algebra-residual");
  EXPECT_EQ(by_f["status"], "max_iterations");
  EXPECT_EQ(by_f["iterations"], 100);
  for (const json& rec : by_f["trace"]) EXPECT_GT(rec["residual"].get<double>(), 0.5);
  EXPECT_EQ(by_algebra["status"], "converged");
  EXPECT_LT(by_algebra["iterations"].get<int>(), 100);
  EXPECT_LE(by_algebra["algebra_residual"].get<double>(), 0.5);
  EXPECT_GT(by_algebra["residual"].get<double>(), 0.5);  // the returned y does not solve f(y) = 0 to tol
  auto bad = c.Post("/api/v1/solve", R"({"stopping":"f-tilde"})", "application/json");
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->status, 400);
  EXPECT_EQ(json::parse(bad->body)["error"]["field"], "stopping");
}

TEST_F(Routes, SweepIntegrateAndWorkPrecision) {
  auto c = client();
  auto sweep = c.Post("/api/v1/sweep",
                      R"({"problem":"paper-linear","methods":["fixed-point","newton-group"],"differential":"exact","n":[3,4],"h":[0.25,0.5]})",
                      "application/json");
  ASSERT_TRUE(sweep);
  ASSERT_EQ(sweep->status, 200) << sweep->body;
  const json s = json::parse(sweep->body);
  ASSERT_EQ(s["cells"].size(), 8u);
  for (const char* field : {"method", "n", "h", "status", "reason", "iterations", "rate", "residual"}) {
    EXPECT_TRUE(s["cells"][0].contains(field)) << field;
  }
  auto integ = c.Post("/api/v1/integrate", R"({"problem":"rigid-body","h":0.1,"t_end":0.5,"frames":3})", "application/json");
  ASSERT_TRUE(integ);
  ASSERT_EQ(integ->status, 200) << integ->body;
  const json i = json::parse(integ->body);
  EXPECT_EQ(i["steps"].size(), 5u);
  for (const char* field : {"status", "reason", "steps", "global_error", "energy_drift", "orthogonality_error", "y", "frames",
                            "frame_times", "frame_steps", "cpu_seconds", "reference_seconds"}) {
    EXPECT_TRUE(i.contains(field)) << field;
  }
  EXPECT_EQ(i["frame_steps"], json::parse("[0, 1, 2, 3, 4, 5]"));  // 5 steps, frames 3: every floor(5 / 3) = 1st
  // Without its reference: the same run (the same y), no global error, and no time spent on one.
  auto bare = c.Post("/api/v1/integrate", R"({"problem":"rigid-body","h":0.1,"t_end":0.5,"frames":3,"reference":false})",
                     "application/json");
  ASSERT_TRUE(bare);
  ASSERT_EQ(bare->status, 200) << bare->body;
  const json b = json::parse(bare->body);
  EXPECT_EQ(b["y"], i["y"]);
  EXPECT_EQ(b["status"], "converged");
  EXPECT_TRUE(b["global_error"].is_null()) << b["global_error"];
  EXPECT_TRUE(b["reference_error"].is_null()) << b["reference_error"];
  EXPECT_EQ(b["reference_seconds"].get<double>(), 0.0);
  EXPECT_GT(i["global_error"].get<double>(), 0.0);
  EXPECT_EQ(i["h"].get<double>(), 0.1);
  EXPECT_TRUE(i["warnings"].is_array() && i["warnings"].empty()) << i["warnings"];
  auto wp = c.Post("/api/v1/work-precision",
                   R"({"problem":"rigid-body","t_end":0.5,"h":[0.1,0.05],"choices":[{"integrator":"implicit-euler","method":"newton-group","differential":"exact"},{"integrator":"dirk-cg2","method":"newton-group","differential":"exact"}]})",
                   "application/json");
  ASSERT_TRUE(wp);
  ASSERT_EQ(wp->status, 200) << wp->body;
  const json w = json::parse(wp->body);
  ASSERT_EQ(w["series"].size(), 2u);
  EXPECT_EQ(w["series"][1]["choice"]["integrator"], "dirk-cg2");
  EXPECT_EQ(w["series"][0]["points"].size(), 2u);
  for (const char* field : {"h", "cpu_seconds", "error", "status", "iterations"}) {
    EXPECT_TRUE(w["series"][0]["points"][0].contains(field)) << field;
  }
  // Two converged points show no consistent slopes: no order, and the reason says so.
  for (const json& s : w["series"]) {
    EXPECT_TRUE(s["fitted_order"].is_null()) << s.dump();
    EXPECT_NE(s["fit_reason"].get<std::string>().find("at least 3"), std::string::npos) << s.dump();
  }
}

TEST_F(Routes, RenderFramesAndHeatmap) {
  auto c = client();
  auto frames = c.Post("/api/v1/render/frames", R"({"n":3,"h":0.5,"width":128,"height":128})", "application/json");
  ASSERT_TRUE(frames);
  ASSERT_EQ(frames->status, 200) << frames->body;
  EXPECT_EQ(frames->get_header_value("Content-Type"), "image/png");
  EXPECT_TRUE(is_png(frames->body));
  auto trajectory = c.Post("/api/v1/render/frames", R"({"problem":"rigid-body","h":0.1,"t_end":1,"width":128,"height":128})", "application/json");
  ASSERT_TRUE(trajectory);
  ASSERT_EQ(trajectory->status, 200) << trajectory->body;
  EXPECT_TRUE(is_png(trajectory->body));
  auto frames_get = c.Get("/api/v1/render/frames?n=3&h=0.5&method=newton-algebra&width=96&height=96");
  ASSERT_TRUE(frames_get);
  ASSERT_EQ(frames_get->status, 200) << frames_get->body;
  EXPECT_TRUE(is_png(frames_get->body));
  // upto (the dashboard's slider) draws iterates 0..upto: the same picture as the solve stopped after upto
  // iterations, and unlike the full run's.
  const std::string solve = R"({"n":3,"h":0.5,"method":"newton-algebra","width":96,"height":96)";
  auto first_two = c.Post("/api/v1/render/frames", solve + R"(,"upto":1})", "application/json");
  auto stopped = c.Post("/api/v1/render/frames", solve + R"(,"max_iterations":1})", "application/json");
  ASSERT_TRUE(first_two && stopped);
  ASSERT_EQ(first_two->status, 200) << first_two->body;
  ASSERT_EQ(stopped->status, 200) << stopped->body;
  EXPECT_EQ(first_two->body, stopped->body);
  EXPECT_NE(first_two->body, frames_get->body);
  // A trajectory of 11 frames: upto 10 is the whole picture, upto 11 names the field.
  const std::string steps = R"({"problem":"rigid-body","h":0.1,"t_end":1,"frames":11,"width":96,"height":96)";
  auto whole = c.Post("/api/v1/render/frames", steps + "}", "application/json");
  auto last = c.Post("/api/v1/render/frames", steps + R"(,"upto":10})", "application/json");
  auto beyond = c.Post("/api/v1/render/frames", steps + R"(,"upto":11})", "application/json");
  ASSERT_TRUE(whole && last && beyond);
  ASSERT_EQ(last->status, 200) << last->body;
  EXPECT_EQ(whole->body, last->body);
  EXPECT_EQ(beyond->status, 422);
  EXPECT_EQ(json::parse(beyond->body)["error"]["field"], "upto");
  auto not_so3 = c.Post("/api/v1/render/frames", R"({"n":4,"h":0.5})", "application/json");
  ASSERT_TRUE(not_so3);
  EXPECT_EQ(not_so3->status, 422);
  EXPECT_EQ(json::parse(not_so3->body)["error"]["field"], "n");

  const std::string sweep = R"({"methods":["newton-group"],"n":[3,4],"h":[0.25,0.5],"differential":"exact")";
  auto heat = c.Post("/api/v1/render/heatmap", sweep + R"(,"metric":"iterations"})", "application/json");
  ASSERT_TRUE(heat);
  ASSERT_EQ(heat->status, 200) << heat->body;
  EXPECT_TRUE(is_png(heat->body));
  auto result = c.Post("/api/v1/sweep", sweep + "}", "application/json");
  ASSERT_TRUE(result);
  auto from_result = c.Post("/api/v1/render/heatmap", R"({"metric":"residual","sweep":)" + result->body + "}", "application/json");
  ASSERT_TRUE(from_result);
  ASSERT_EQ(from_result->status, 200) << from_result->body;
  EXPECT_TRUE(is_png(from_result->body));
  // A result with its request beside it: drawn, not run again, and titled by the request (problem, group,
  // solver); a cell outside that request's grid is refused naming it.
  const std::string titled = R"({"problem":"paper-sine","methods":["newton-group"],"n":[3,4],"h":[0.25,0.5],"differential":"exact","format":"svg","sweep":)";
  auto named = c.Post("/api/v1/render/heatmap", titled + result->body + "}", "application/json");
  ASSERT_TRUE(named);
  ASSERT_EQ(named->status, 200) << named->body;
  EXPECT_NE(svg_words(named->body).find("Where each method converges: paper-sine on SO(N)"), std::string::npos);
  auto outside = c.Post("/api/v1/render/heatmap",
                        R"({"problem":"paper-sine","methods":["newton-group"],"n":[3],"h":[0.25,0.5],"differential":"exact","sweep":)" +
                            result->body + "}", "application/json");
  ASSERT_TRUE(outside);
  EXPECT_EQ(outside->status, 400) << outside->body;
  EXPECT_EQ(json::parse(outside->body)["error"]["field"], "sweep.cells[2]");  // the first cell at n = 4
  auto heat_get = c.Get("/api/v1/render/heatmap?methods=newton-group&n=3,4&h=[0.25,0.5]&differential=exact");
  ASSERT_TRUE(heat_get);
  ASSERT_EQ(heat_get->status, 200) << heat_get->body;
  EXPECT_TRUE(is_png(heat_get->body));
  // GET fills what it lacks as POST does: here the paper's 21 step sizes, the same picture byte for byte.
  auto get_default_h = c.Get("/api/v1/render/heatmap?problem=paper-linear&differential=exact&methods=newton-group&n=3");
  auto post_default_h = c.Post("/api/v1/render/heatmap",
                               R"({"problem":"paper-linear","differential":"exact","methods":["newton-group"],"n":[3]})",
                               "application/json");
  ASSERT_TRUE(get_default_h && post_default_h);
  ASSERT_EQ(get_default_h->status, 200) << get_default_h->body;
  EXPECT_TRUE(is_png(get_default_h->body));
  EXPECT_EQ(get_default_h->body, post_default_h->body);
  // format=svg: the same picture as SVG, its caption as text; another format is refused naming the field.
  auto svg = c.Get("/api/v1/render/heatmap?problem=paper-linear&differential=exact&methods=newton-group&n=3,4&h=1,2&format=svg");
  ASSERT_TRUE(svg);
  ASSERT_EQ(svg->status, 200) << svg->body;
  EXPECT_EQ(svg->get_header_value("Content-Type"), "image/svg+xml");
  EXPECT_EQ(svg->body.rfind("<svg ", 0), 0u);
  EXPECT_NE(svg_words(svg->body).find("Where each method converges: paper-linear on SO(N)"), std::string::npos);
  EXPECT_NE(svg->body.find(">N = 3\u20264 \u00b7 h = 2\u2070\u20262\u00b9"), std::string::npos);  // wrapped between facts
  EXPECT_NE(svg->body.find("differential exact \u00b7 tol 1e-13"), std::string::npos);
  auto basins_svg = c.Post("/api/v1/render/basins",
                           R"({"problem":"paper-linear","n":3,"h":4,"size":8,"methods":["newton-group","newton-algebra"],"format":"svg"})",
                           "application/json");
  ASSERT_TRUE(basins_svg);
  ASSERT_EQ(basins_svg->status, 200) << basins_svg->body;
  EXPECT_EQ(basins_svg->get_header_value("Content-Type"), "image/svg+xml");
  EXPECT_NE(svg_words(basins_svg->body).find("From which starts each method converges: paper-linear on SO(3), h = 2\u00b2"),
            std::string::npos);
  std::size_t images = 0;
  for (std::size_t at = basins_svg->body.find("<image "); at != std::string::npos; at = basins_svg->body.find("<image ", at + 1)) ++images;
  EXPECT_EQ(images, 2u);  // one raster panel per method
  auto wp_svg = c.Post("/api/v1/render/work-precision",
                       R"({"problem":"rigid-body","h":[0.25,0.125],"choices":[{"integrator":"implicit-euler"}],"format":"svg"})",
                       "application/json");
  ASSERT_TRUE(wp_svg);
  ASSERT_EQ(wp_svg->status, 200) << wp_svg->body;
  EXPECT_NE(wp_svg->body.find(">2\u207b\u00b3</text>"), std::string::npos);  // the h = 1/8 marker's label
  auto bad_format = c.Get("/api/v1/render/heatmap?methods=newton-group&n=3&h=1&format=pdf");
  ASSERT_TRUE(bad_format);
  EXPECT_EQ(bad_format->status, 400);
  EXPECT_EQ(json::parse(bad_format->body)["error"]["field"], "format");
  auto bad_metric = c.Post("/api/v1/render/heatmap", sweep + R"(,"metric":"speed"})", "application/json");
  ASSERT_TRUE(bad_metric);
  EXPECT_EQ(bad_metric->status, 400);
  EXPECT_EQ(json::parse(bad_metric->body)["error"]["field"], "metric");
  auto too_wide = c.Post("/api/v1/render/frames", R"({"n":3,"width":100000})", "application/json");
  ASSERT_TRUE(too_wide);
  EXPECT_EQ(too_wide->status, 400);
  EXPECT_EQ(json::parse(too_wide->body)["error"]["field"], "width");
}

TEST_F(Routes, StaticFilesStayInsideTheWebRoot) {
  auto c = client();
  auto index = c.Get("/");
  ASSERT_TRUE(index);
  EXPECT_EQ(index->status, 200);
  EXPECT_NE(index->body.find("lienewton"), std::string::npos);
  auto js = c.Get("/app.js");
  ASSERT_TRUE(js);
  EXPECT_EQ(js->status, 200);
  EXPECT_EQ(js->get_header_value("Content-Type"), "text/javascript; charset=utf-8");
  auto sub = c.Get("/sub/");
  ASSERT_TRUE(sub);
  EXPECT_EQ(sub->body, "sub");
  auto range = c.Get("/app.js", {{"Range", "bytes=0-5"}});
  ASSERT_TRUE(range);
  EXPECT_EQ(range->status, 206);
  EXPECT_EQ(range->body, "export");
  // Traversal, encoded traversal, symlinks out of the root and dotfiles all end as 404 (or 400), never SECRET.
  for (const char* path : {"/../secret.txt", "/%2e%2e/secret.txt", "/sub/../../secret.txt", "/link.txt", "/.hidden",
                           "/..%2fsecret.txt"}) {
    const std::string answer = testing::raw_http(server_->port, std::string("GET ") + path + " HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n");
    EXPECT_EQ(answer.find("SECRET"), std::string::npos) << path;
    const int status = testing::raw_status(answer);
    EXPECT_TRUE(status == 404 || status == 400) << path << " -> " << status;
  }
  auto multi = c.Get("/app.js", {{"Range", "bytes=0-1,3-4"}});
  ASSERT_TRUE(multi);
  EXPECT_EQ(multi->status, 416);
  auto outside = c.Get("/app.js", {{"Range", "bytes=1000-2000"}});
  ASSERT_TRUE(outside);
  EXPECT_EQ(outside->status, 416);
}

// "/" is a route (the OpenAPI document lists it) but a static file all the same: one range is exactly those
// bytes with their Content-Range, several are refused, never expanded.
TEST_F(Routes, DashboardRootAnswersByteRangesAsAStaticFile) {
  auto c = client();
  auto whole = c.Get("/");
  ASSERT_TRUE(whole);
  ASSERT_EQ(whole->status, 200);
  auto range = c.Get("/", {{"Range", "bytes=0-9"}});
  ASSERT_TRUE(range);
  EXPECT_EQ(range->status, 206);
  EXPECT_EQ(range->get_header_value("Content-Range"), "bytes 0-9/" + std::to_string(whole->body.size()));
  EXPECT_EQ(range->body, whole->body.substr(0, 10));
  auto multi = c.Get("/", {{"Range", "bytes=0-1,3-4"}});
  ASSERT_TRUE(multi);
  EXPECT_EQ(multi->status, 416);
  EXPECT_EQ(json::parse(multi->body)["error"]["code"], "multiple_ranges");
  // An API answer under a Range is still whole.
  auto openapi = c.Get("/openapi.json", {{"Range", "bytes=0-9"}});
  ASSERT_TRUE(openapi);
  EXPECT_EQ(openapi->status, 200);
  EXPECT_FALSE(openapi->has_header("Content-Range"));
  EXPECT_TRUE(json::accept(openapi->body));
}

// The dashboard runs only this origin's scripts and styles, cannot be framed, and its URLs (which hold the
// request, a user's program included) are sent as referrer to this origin only.
TEST_F(Routes, DashboardPagesCarrySecurityHeaders) {
  auto c = client();
  for (const char* path : {"/", "/index.html", "/app.js"}) {
    auto page = c.Get(path);
    ASSERT_TRUE(page);
    ASSERT_EQ(page->status, 200) << path;
    const std::string csp = page->get_header_value("Content-Security-Policy");
    for (const char* directive : {"default-src 'self'", "script-src 'self'", "style-src 'self'", "object-src 'none'",
                                  "frame-ancestors 'none'"}) {
      EXPECT_NE(csp.find(directive), std::string::npos) << path << ": " << csp;
    }
    EXPECT_EQ(csp.find("unsafe"), std::string::npos) << csp;
    EXPECT_EQ(page->get_header_value("X-Frame-Options"), "DENY") << path;
    EXPECT_EQ(page->get_header_value("Referrer-Policy"), "same-origin") << path;
    EXPECT_EQ(page->get_header_value("X-Content-Type-Options"), "nosniff") << path;
    EXPECT_EQ(page->get_header_value_count("Content-Security-Policy"), 1u) << path;
  }
}

TEST_F(Routes, StaticFilesRevalidateByETag) {
  auto c = client();
  const auto file = server_->base / "web" / "validated.txt";
  std::ofstream(file) << "first version";
  auto first = c.Get("/validated.txt");
  ASSERT_TRUE(first);
  ASSERT_EQ(first->status, 200);
  const std::string etag = first->get_header_value("ETag");
  ASSERT_EQ(etag.size(), 20u) << etag;  // W/"16 hex digits"
  EXPECT_EQ(first->get_header_value("Cache-Control"), "no-cache");
  auto again = c.Get("/validated.txt", {{"If-None-Match", etag}});
  ASSERT_TRUE(again);
  EXPECT_EQ(again->status, 304);
  EXPECT_TRUE(again->body.empty());
  EXPECT_EQ(again->get_header_value("ETag"), etag);
  // A list, the strong form of the same tag and "*" all match; another tag does not.
  for (const std::string& header : {"\"0000000000000000\", " + etag, etag.substr(2), std::string("*")}) {
    auto listed = c.Get("/validated.txt", {{"If-None-Match", header}});
    ASSERT_TRUE(listed);
    EXPECT_EQ(listed->status, 304) << header;
  }
  auto other = c.Get("/validated.txt", {{"If-None-Match", "\"0000000000000000\""}});
  ASSERT_TRUE(other);
  EXPECT_EQ(other->status, 200);
  EXPECT_EQ(other->body, "first version");
  // A changed file gets a new tag: the old one no longer matches.
  std::ofstream(file) << "second version";
  auto changed = c.Get("/validated.txt", {{"If-None-Match", etag}});
  ASSERT_TRUE(changed);
  EXPECT_EQ(changed->status, 200);
  EXPECT_EQ(changed->body, "second version");
  EXPECT_NE(changed->get_header_value("ETag"), etag);
}

TEST_F(Routes, OpenApiRevalidatesByETag) {
  auto c = client();
  auto first = c.Get("/openapi.json");
  ASSERT_TRUE(first);
  ASSERT_EQ(first->status, 200);
  const std::string etag = first->get_header_value("ETag");
  ASSERT_FALSE(etag.empty());
  auto again = c.Get("/openapi.json", {{"If-None-Match", etag}});
  ASSERT_TRUE(again);
  EXPECT_EQ(again->status, 304);
  EXPECT_TRUE(again->body.empty());
  auto other = c.Get("/openapi.json", {{"If-None-Match", "W/\"0000000000000000\""}});
  ASSERT_TRUE(other);
  EXPECT_EQ(other->status, 200);
  EXPECT_EQ(other->body, first->body);
}

TEST_F(Routes, GetRendersRevalidateByETag) {
  auto c = client();
  const std::string url = "/api/v1/render/frames?n=3&h=0.5&width=64&height=64";
  auto first = c.Get(url);
  ASSERT_TRUE(first);
  ASSERT_EQ(first->status, 200) << first->body;
  const std::string etag = first->get_header_value("ETag");
  ASSERT_FALSE(etag.empty());
  EXPECT_EQ(first->get_header_value("Cache-Control"), "no-cache");
  auto again = c.Get(url, {{"If-None-Match", etag}});
  ASSERT_TRUE(again);
  EXPECT_EQ(again->status, 304);
  EXPECT_TRUE(again->body.empty());
  // The same request spelled with its parameters in another order is the same canonical request.
  auto reordered = c.Get("/api/v1/render/frames?height=64&width=64&h=0.5&n=3", {{"If-None-Match", etag}});
  ASSERT_TRUE(reordered);
  EXPECT_EQ(reordered->status, 304);
  // A changed request draws anew; "*" does not stand in for a picture not yet drawn; POST is never cached.
  auto changed = c.Get("/api/v1/render/frames?n=3&h=0.25&width=64&height=64", {{"If-None-Match", etag}});
  ASSERT_TRUE(changed);
  EXPECT_EQ(changed->status, 200);
  EXPECT_TRUE(is_png(changed->body));
  EXPECT_NE(changed->get_header_value("ETag"), etag);
  auto star = c.Get(url, {{"If-None-Match", "*"}});
  ASSERT_TRUE(star);
  EXPECT_EQ(star->status, 200);
  auto post = c.Post("/api/v1/render/frames", R"({"n":3,"h":0.5,"width":64,"height":64})", "application/json");
  ASSERT_TRUE(post);
  ASSERT_EQ(post->status, 200);
  EXPECT_EQ(post->get_header_value("Cache-Control"), "no-store");
  EXPECT_FALSE(post->has_header("ETag"));
}

TEST_F(Routes, RequestIdIsEchoedOnlyWhenSafe) {
  auto c = client();
  auto given = c.Get("/livez", {{"X-Request-Id", "trace-123.abc_X"}});
  ASSERT_TRUE(given);
  EXPECT_EQ(given->get_header_value("X-Request-Id"), "trace-123.abc_X");
  auto bad = c.Get("/livez", {{"X-Request-Id", "no spaces<script>"}});
  ASSERT_TRUE(bad);
  const std::string id = bad->get_header_value("X-Request-Id");
  EXPECT_NE(id, "no spaces<script>");
  EXPECT_EQ(id.size(), 16u);
}

}  // namespace
}  // namespace lienewton::service
