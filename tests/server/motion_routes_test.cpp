// render/motion end to end: an animated WebP with a frame per state shown, the still of one state, the GET form,
// the CLI's table of render routes, and the errors.
#include <gtest/gtest.h>
#include <webp/demux.h>

#include <set>

#include "../render/png_decode.hpp"
#include "server/render_requests.hpp"
#include "test_server.hpp"

namespace lienewton::service {
namespace {

class MotionRoutes : public testing::SharedServerTest {};

struct WebpInfo {
  bool valid = false;
  unsigned width = 0, height = 0, frames = 0;
  std::string xmp;  // the metadata packet, or empty
};

WebpInfo webp_info(const std::string& body) {
  const WebPData data{reinterpret_cast<const std::uint8_t*>(body.data()), body.size()};
  WebPDemuxer* demux = WebPDemux(&data);
  if (!demux) return {};
  WebpInfo info{true, WebPDemuxGetI(demux, WEBP_FF_CANVAS_WIDTH), WebPDemuxGetI(demux, WEBP_FF_CANVAS_HEIGHT),
                WebPDemuxGetI(demux, WEBP_FF_FRAME_COUNT), {}};
  WebPChunkIterator chunk;
  if (WebPDemuxGetChunk(demux, "XMP ", 1, &chunk)) {
    info.xmp.assign(reinterpret_cast<const char*>(chunk.chunk.bytes), chunk.chunk.size);
    WebPDemuxReleaseChunkIterator(&chunk);
  }
  WebPDemuxDelete(demux);
  return info;
}

// The value of attribute name="..." in an XMP packet.
std::string xmp_attribute(const std::string& xmp, const std::string& name) {
  const std::size_t from = xmp.find(name + "=\"");
  if (from == std::string::npos) return {};
  const std::size_t begin = from + name.size() + 2;
  return xmp.substr(begin, xmp.find('"', begin) - begin);
}

TEST_F(MotionRoutes, AnIntegrationAnimatesOneFramePerShownState) {
  auto res = client().Post("/api/v1/render/motion",
                           R"({"problem":"heavy-top","integrator":"rkmk-gauss2","t_end":0.25,"frames":12,)"
                           R"("width":160,"height":128,"frame_ms":30})",
                           "application/json");
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200) << res->body;
  EXPECT_EQ(res->get_header_value("Content-Type"), "image/webp");
  const WebpInfo info = webp_info(res->body);
  ASSERT_TRUE(info.valid);
  EXPECT_EQ(info.width, 160u);
  EXPECT_EQ(info.height, 128u);
  EXPECT_EQ(info.frames, 13u);  // y(0) and the 12 evenly spaced states after it
}

// What the picture cannot say is a header: implicit Euler on the heavy top drifts its invariants (by 5 % and 54 %
// over t = 2) though every step converges; rkmk-gauss2 at the same step keeps them (to about 1e-6).
TEST_F(MotionRoutes, AnIntegrationsWarningsAreAHeader) {
  const std::string request = R"({"problem":"heavy-top","t_end":0.25,"frames":4,"width":96,"height":96,"format":"png",)";
  const nlohmann::json integration = post("/api/v1/integrate", R"({"problem":"heavy-top","t_end":0.25,)"
                                                               R"("integrator":"implicit-euler","reference":false})");
  ASSERT_FALSE(integration["warnings"].empty());
  for (const char* route : {"/api/v1/render/motion", "/api/v1/render/frames", "/api/v1/render/invariants"}) {
    auto euler = client().Post(route, request + R"("integrator":"implicit-euler"})", "application/json");
    ASSERT_TRUE(euler);
    ASSERT_EQ(euler->status, 200) << route << ": " << euler->body;
    EXPECT_EQ(euler->get_header_value(kWarningsHeader), "invariant_drift") << route;
    auto gauss = client().Post(route, request + R"("integrator":"rkmk-gauss2"})", "application/json");
    ASSERT_TRUE(gauss);
    ASSERT_EQ(gauss->status, 200) << route << ": " << gauss->body;
    EXPECT_FALSE(gauss->has_header(kWarningsHeader)) << route << ": " << gauss->get_header_value(kWarningsHeader);
  }
  EXPECT_EQ(integration["warnings"][0]["code"], "invariant_drift");
}

TEST_F(MotionRoutes, ASolvesIteratesAreItsFrames) {
  const nlohmann::json solve = post("/api/v1/solve", R"({"problem":"rigid-body","h":1})");
  auto res = client().Post("/api/v1/render/motion", R"({"problem":"rigid-body","h":1,"width":128,"height":128})",
                           "application/json");
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200) << res->body;
  const WebpInfo info = webp_info(res->body);
  EXPECT_EQ(info.frames, solve["iterations"].get<unsigned>() + 1);  // y_0, ..., y_n
  EXPECT_EQ(xmp_attribute(info.xmp, "lienewton:timeName"), "n");
  std::string iterates;
  for (unsigned n = 0; n < info.frames; ++n) iterates.append(n ? " " : "").append(std::to_string(n));
  EXPECT_EQ(xmp_attribute(info.xmp, "lienewton:frameTimes"), iterates);
}

// 300 iterates of the fixed point, which does not converge at h = 4, are shown as 101 evenly spaced: the metadata
// names which (n = 0, 3, 6, ..., 300).
TEST_F(MotionRoutes, ALongSolveShowsAHundredAndOneOfItsIterates) {
  auto res = client().Post("/api/v1/render/motion",
                           R"({"n":3,"h":4,"method":"fixed-point","max_iterations":300,"width":96,"height":96})",
                           "application/json");
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200) << res->body;
  const WebpInfo info = webp_info(res->body);
  ASSERT_EQ(info.frames, 101u);
  std::string iterates;
  for (unsigned k = 0; k <= 100; ++k) iterates.append(k ? " " : "").append(std::to_string(3 * k));
  EXPECT_EQ(xmp_attribute(info.xmp, "lienewton:frameTimes"), iterates);
}

// An integration's frame times are its states' times: t = 0 first, t_end last, increasing.
TEST_F(MotionRoutes, AnAnimationNamesEachFramesTime) {
  auto res = client().Post("/api/v1/render/motion",
                           R"({"problem":"rigid-body","t_end":1,"h":0.125,"frames":4,"width":96,"height":96})",
                           "application/json");
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200) << res->body;
  const WebpInfo info = webp_info(res->body);
  EXPECT_EQ(xmp_attribute(info.xmp, "lienewton:timeName"), "t");
  EXPECT_EQ(xmp_attribute(info.xmp, "lienewton:frameTimes"), "0 0.25 0.5 0.75 1");
}

TEST_F(MotionRoutes, PngAndSvgShowOneStateAndTheGetFormIsCached) {
  auto png = client().Post("/api/v1/render/motion",
                           R"({"problem":"chain","n":3,"t_end":0.5,"frames":8,"format":"png","upto":4,"width":200,"height":200})",
                           "application/json");
  ASSERT_TRUE(png);
  ASSERT_EQ(png->status, 200) << png->body;
  EXPECT_EQ(png->get_header_value("Content-Type"), "image/png");
  const render::testing::DecodedImage image =
      render::testing::decode_png(std::vector<std::uint8_t>(png->body.begin(), png->body.end()));
  EXPECT_EQ(image.width, 200);
  auto svg = client().Post("/api/v1/render/motion", R"({"problem":"rigid-body","t_end":2,"format":"svg"})",
                           "application/json");
  ASSERT_TRUE(svg);
  ASSERT_EQ(svg->status, 200) << svg->body;
  EXPECT_EQ(svg->get_header_value("Content-Type"), "image/svg+xml");
  EXPECT_NE(svg->body.find("<svg"), std::string::npos);
  // GET, for <img src>: an integration's fields beside a solve's; a repeat answers 304 from its ETag.
  const std::string path = "/api/v1/render/motion?problem=heavy-top&t_end=0.1&frames=4&width=96&height=96";
  auto get = client().Get(path);
  ASSERT_TRUE(get);
  ASSERT_EQ(get->status, 200) << get->body;
  EXPECT_EQ(webp_info(get->body).frames, 5u);
  auto again = client().Get(path, {{"If-None-Match", get->get_header_value("ETag")}});
  ASSERT_TRUE(again);
  EXPECT_EQ(again->status, 304);
}

TEST_F(MotionRoutes, BadPicturesAreRefusedNamingTheField) {
  const std::string opening = R"({"problem":"heavy-top","t_end":0.1,)";
  const std::pair<const char*, const char*> invalid[] = {{R"("format":"gif"})", "format"},
                                                         {R"("frame_ms":0})", "frame_ms"},
                                                         {R"("frames":1001})", "frames"},
                                                         {R"("width":10})", "width"},
                                                         {R"("kind":"sweep"})", "kind"}};
  for (const auto& [rest, field] : invalid) EXPECT_EQ(post("/api/v1/render/motion", opening + rest, 400)["error"]["field"], field);
  // Past the last state shown: the request is well formed, the picture cannot be drawn.
  expect_422_naming("/api/v1/render/motion", opening, {{R"("frames":4,"upto":5,"format":"png"})", "upto"}});
  // A group without bodies: SO(4) has no rotation frames to draw.
  const nlohmann::json e = post("/api/v1/render/motion", R"({"problem":"paper-linear","n":4})", 422);
  EXPECT_EQ(e["error"]["field"], "n");
}

TEST(RenderRouteTable, NamesEachRouteOnceAndFindsThem) {
  std::set<std::string> names;
  for (const RenderRoute& r : render_routes()) {
    EXPECT_TRUE(names.insert(r.name).second) << r.name;
    EXPECT_EQ(find_render_route(r.name), &r);
  }
  EXPECT_EQ(find_render_route("movie"), nullptr);
  EXPECT_TRUE(find_render_route("motion")->integrations_too);
}

}  // namespace
}  // namespace lienewton::service
