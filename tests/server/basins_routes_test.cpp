// Basin maps over HTTP: the plain answer, the NDJSON stream (grid, rows in order, summary),
// caps and errors naming the field, byte-identical JSON for 1 and 2 threads, and the PNG.
#include <gtest/gtest.h>

#include <set>
#include <sstream>

#include "../render/png_decode.hpp"
#include "core/basins.hpp"
#include "render/basin_scene.hpp"
#include "render/colormap.hpp"
#include "server/json_codec.hpp"
#include "test_server.hpp"

namespace lienewton::service {
namespace {

using render::testing::decode_png;

const std::string kMap = R"({"problem":"paper-linear","n":3,"h":4,"differential":"exact","size":12})";

class BasinRoutes : public testing::SharedServerTest {};

TEST_F(BasinRoutes, PlainAnswerHoldsGridRowsRootsAndSummary) {
  auto c = client();
  auto res = c.Post("/api/v1/basins", kMap, "application/json");
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200) << res->body;
  const json map = json::parse(res->body);
  ASSERT_EQ(map["grid"]["a"].size(), 12u);
  EXPECT_NEAR(map["grid"]["a"][0].get<double>(), -M_PI * 11 / 12, 1e-15);
  ASSERT_EQ(map["rows"].size(), 12u);
  ASSERT_EQ(map["methods"].size(), 3u);  // every method by default
  EXPECT_TRUE(map["complete"].get<bool>());
  for (const json& m : map["methods"]) {
    int converged = 0, counted = 0;
    std::set<int> roots;
    double iterations = 0;
    for (const json& row : map["rows"]) {
      for (const json& per : row["methods"]) {
        if (per["method"] != m["method"]) continue;
        for (std::size_t c = 0; c < 12; ++c) {
          ++counted;
          if (per["status"][c] != "converged") {
            EXPECT_TRUE(per["root"][c].is_null());
            continue;
          }
          ++converged;
          iterations += per["iterations"][c].get<int>();
          roots.insert(per["root"][c].get<int>());
        }
      }
    }
    EXPECT_EQ(counted, 144);
    EXPECT_EQ(m["converged"], converged);
    EXPECT_DOUBLE_EQ(m["converged_fraction"].get<double>(), converged / 144.0);
    EXPECT_EQ(m["basins"], roots.size());
    if (converged) {
      EXPECT_DOUBLE_EQ(m["mean_iterations"].get<double>(), iterations / converged);
    }
  }
  EXPECT_GE(map["roots"].size(), 2u);
}

// A shard answers its rows only (r % count == index, the full map's rows) and says which part it is.
TEST_F(BasinRoutes, ShardAnswersItsRowsAndSaysWhichPartItIs) {
  auto c = client();
  const json whole = json::parse(c.Post("/api/v1/basins", kMap, "application/json")->body);
  json request = json::parse(kMap);
  request["shard"] = {{"index", 1}, {"count", 5}};
  auto res = c.Post("/api/v1/basins", request.dump(), "application/json");
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200) << res->body;
  const json part = json::parse(res->body);
  EXPECT_EQ(part["shard"]["index"], 1);
  EXPECT_EQ(part["shard"]["count"], 5);
  EXPECT_EQ(part["shard"]["rows"], json::parse("[1, 6, 11]"));
  EXPECT_EQ(part["shard"]["request"], json::parse(kMap));
  EXPECT_TRUE(part["complete"]);
  ASSERT_EQ(part["rows"].size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    const std::size_t row = 1 + 5 * k;
    EXPECT_EQ(part["rows"][k]["row"], row);
    for (std::size_t m = 0; m < 3; ++m) {
      EXPECT_EQ(part["rows"][k]["methods"][m]["status"], whole["rows"][row]["methods"][m]["status"]);
      EXPECT_EQ(part["rows"][k]["methods"][m]["iterations"], whole["rows"][row]["methods"][m]["iterations"]);
    }
  }
  EXPECT_FALSE(whole.contains("shard"));
}

TEST_F(BasinRoutes, StreamAnnouncesTheGridThenRowsInOrderThenTheSummary) {
  auto c = client();
  httplib::Headers accept{{"Accept", "application/x-ndjson"}};
  auto res = c.Post("/api/v1/basins", accept, kMap, "application/json");
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200);
  EXPECT_EQ(res->get_header_value("Content-Type"), "application/x-ndjson");
  std::vector<json> lines;
  std::istringstream in(res->body);
  for (std::string line; std::getline(in, line);) lines.push_back(json::parse(line));
  ASSERT_EQ(lines.size(), 1u + 12u + 1u);
  EXPECT_EQ(lines.front()["type"], "grid");
  EXPECT_EQ(lines.front()["z"].size(), 3u);
  json streamed_roots = json::array();
  for (int r = 0; r < 12; ++r) {
    const json& row = lines[static_cast<std::size_t>(r) + 1];
    EXPECT_EQ(row["type"], "row");
    EXPECT_EQ(row["row"], r);
    for (const json& root : row["new_roots"]) streamed_roots.push_back(root);
  }
  const json& result = lines.back();
  EXPECT_EQ(result["type"], "result");
  EXPECT_FALSE(result.contains("rows"));
  EXPECT_EQ(result["roots"], streamed_roots);  // each root announced once, with the row that met it first
}

TEST_F(BasinRoutes, CapsAndBadFieldsAreRefusedNamingTheField) {
  auto c = client();
  auto refused = [&](const std::string& path, const std::string& body, int status, const std::string& field) {
    auto res = c.Post(path, body, "application/json");
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, status) << body << " -> " << res->body;
    EXPECT_EQ(json::parse(res->body)["error"]["field"], field) << body;
  };
  refused("/api/v1/basins", R"({"size":100000})", 422, "size");
  refused("/api/v1/basins", R"({"size":512})", 413, "size");  // 3 x 512^2 pixels: beyond --max-output-values
  refused("/api/v1/basins", R"({"size":0})", 400, "size");
  refused("/api/v1/basins", R"({"r":"NaN"})", 400, "r");
  refused("/api/v1/basins", R"({"n":2})", 422, "n");
  refused("/api/v1/basins", R"({"b1":[1,0]})", 400, "b1");
  refused("/api/v1/basins", R"({"b1":[1,0,0],"b2":[2,0,0]})", 422, "b2");
  refused("/api/v1/basins", R"({"method":"newton-group"})", 400, "method");
  refused("/api/v1/basins", R"({"shard":{"index":3,"count":3}})", 422, "shard.index");
  refused("/api/v1/basins", R"({"shard":{"index":-1,"count":3}})", 400, "shard.index");
  refused("/api/v1/basins", R"({"shard":{"index":0}})", 400, "shard");
  refused("/api/v1/sweep", R"({"shard":{"index":2,"count":2}})", 422, "shard.index");
  refused("/api/v1/solve", R"({"n":3,"y0":[[2,0,0],[0,2,0],[0,0,2]]})", 422, "y0");
  refused("/api/v1/solve", R"({"n":3,"y0":[[1,0],[0,1]]})", 400, "y0");
}

// The same map for any thread count: the JSON answer is byte for byte the same (wall time aside).
TEST(BasinJson, ByteIdenticalForOneAndTwoThreads) {
  auto map_json = [](int threads) {
    BasinRequest r = basin_request_from_json(json::parse(kMap), Limits{});
    r.size = 24;
    r.threads = threads;
    json j = to_json(basins(r), r.methods);
    j.erase("seconds");
    return dump(j);
  };
  const std::string one = map_json(1);
  EXPECT_EQ(one, map_json(2));
  EXPECT_GT(one.size(), 1000u);
}

TEST_F(BasinRoutes, PngHasOnePanelPerMethodInRootAndFailureColours) {
  auto c = client();
  const std::string body =
      R"({"problem":"paper-linear","n":3,"h":32,"differential":"exact","size":16,"methods":["fixed-point","newton-group"]})";
  auto res = c.Post("/api/v1/render/basins", body, "application/json");
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200) << res->body;
  EXPECT_EQ(res->get_header_value("Content-Type"), "image/png");
  const std::vector<std::uint8_t> bytes(res->body.begin(), res->body.end());
  const auto image = decode_png(bytes);
  // The map's own answer says what must be drawn: each failure class that occurs, and root 0's hue (shaded).
  auto plain = c.Post("/api/v1/basins", body, "application/json");
  ASSERT_TRUE(plain);
  const json map = json::parse(plain->body);
  std::set<std::string> failures;
  bool any_converged = false;
  for (const json& m : map["methods"])
    for (const auto& [status, count] : m["statuses"].items()) {
      if (status != "converged") failures.insert(status);
      else any_converged = true;
    }
  for (const std::string& s : failures) {
    const render::Color want = render::status_color(*status_from_string(s));
    bool found = false;
    for (int y = 0; y < image.height && !found; ++y)
      for (int x = 0; x < image.width && !found; ++x) found = image.at(x, y) == want;
    EXPECT_TRUE(found) << "failure colour of " << s;
  }
  if (any_converged) {
    const render::Color root0 = render::root_color(0);
    bool found = false;
    for (int y = 0; y < image.height && !found; ++y)
      for (int x = 0; x < image.width && !found; ++x) found = image.at(x, y) == root0;  // lightest shade in legend
    EXPECT_TRUE(found);
  }
  // Between two panels the end ticks (r of the first, -r of the second) leave a clear column: the pixel
  // column midway through the gap is the background from the panels' bottom down through the tick labels.
  const BasinResult result = basins(basin_request_from_json(json::parse(body), Limits{}));
  const render::BasinLayout layout = render::layout_basins(result, 0, 0);
  ASSERT_EQ(image.width, layout.width);
  // The caption (title: problem, group, h; subtitle: the starts, differential, tol) is a band above the layout.
  const int band = image.height - layout.height;
  EXPECT_GT(band, 0);
  EXPECT_GT(image.count_not(image.at(0, 0), 0, 0, image.width / 2, band), 200);
  const int middle = layout.left + layout.panel_size + layout.gap / 2;
  const render::Color background = image.at(0, 0);
  for (int y = band + layout.top; y < band + layout.top + layout.panel_size + 30; ++y) {
    EXPECT_EQ(image.at(middle, y), background) << "tick labels meet in the gap at y = " << y;
  }
  // The GET form for <img src>.
  auto get = c.Get("/api/v1/render/basins?n=3&h=32&size=8&methods=newton-group,newton-algebra&width=400");
  ASSERT_TRUE(get);
  ASSERT_EQ(get->status, 200) << get->body;
  const std::vector<std::uint8_t> get_bytes(get->body.begin(), get->body.end());
  EXPECT_EQ(decode_png(get_bytes).width, 400);
}

}  // namespace
}  // namespace lienewton::service
