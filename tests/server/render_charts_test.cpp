// The chart routes end to end: PNGs decoded and read for their series colours, legend and errors.
#include <gtest/gtest.h>

#include <set>

#include "../render/png_decode.hpp"
#include "render/series_style.hpp"
#include "server/json_codec.hpp"
#include "test_server.hpp"

namespace lienewton::service {
namespace {

using render::testing::decode_png;
using render::testing::DecodedImage;

// Which of the series colours occur in columns [x0, x1) of the picture.
std::set<std::size_t> series_colors(const DecodedImage& image, int x0, int x1) {
  std::set<std::size_t> found;
  for (int y = 0; y < image.height; ++y) {
    for (int x = x0; x < x1; ++x) {
      for (std::size_t k = 0; k < render::kSeriesColors; ++k) {
        if (image.at(x, y) == render::series_style(k).color) found.insert(k);
      }
    }
  }
  return found;
}

DecodedImage png_of(const httplib::Result& res) {
  const std::vector<std::uint8_t> bytes(res->body.begin(), res->body.end());
  return decode_png(bytes);
}

class RenderCharts : public ::testing::Test {
 protected:
  testing::TestServer server;
};

constexpr const char* kChoices =
    R"([{"integrator":"implicit-euler","method":"newton-group","differential":"exact"},)"
    R"({"integrator":"dirk-cg2","method":"newton-algebra","differential":"finite-difference"},)"
    R"({"integrator":"dirk-cg2","method":"fixed-point","differential":"exact"}])";

TEST_F(RenderCharts, WorkPrecisionDrawsOneColouredSeriesPerChoiceWithALegend) {
  auto c = server.client();
  const std::string body = std::string(R"({"problem":"rigid-body","t_end":0.5,"h":[0.125,0.0625,0.03125],"choices":)") +
                           kChoices + R"(,"width":800,"height":500})";
  auto res = c.Post("/api/v1/render/work-precision", body, "application/json");
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200) << res->body;
  EXPECT_EQ(res->get_header_value("Content-Type"), "image/png");
  const DecodedImage image = png_of(res);
  ASSERT_EQ(image.width, 800);
  ASSERT_EQ(image.height, 500);
  EXPECT_EQ(series_colors(image, 0, image.width).size(), 3u);
  // The legend column (right of the plot) shows all three samples too.
  EXPECT_EQ(series_colors(image, image.width * 2 / 3, image.width).size(), 3u);
  // The GET form, for <img src>: the same picture.
  httplib::Params params{{"problem", "rigid-body"}, {"t_end", "0.5"}, {"h", "0.125,0.0625,0.03125"},
                         {"choices", kChoices}, {"width", "800"}, {"height", "500"}};
  auto get = c.Get("/api/v1/render/work-precision?" + httplib::detail::params_to_query_str(params));
  ASSERT_TRUE(get);
  ASSERT_EQ(get->status, 200) << get->body;
  EXPECT_EQ(series_colors(png_of(get), 0, 800).size(), 3u);
}

TEST_F(RenderCharts, WorkPrecisionRefusesBadPicturesAndRequests) {
  auto c = server.client();
  auto wide = c.Post("/api/v1/render/work-precision", R"({"choices":[{}],"width":5000})", "application/json");
  ASSERT_TRUE(wide);
  EXPECT_EQ(wide->status, 400);
  EXPECT_EQ(json::parse(wide->body)["error"]["field"], "width");
  auto no_choice = c.Post("/api/v1/render/work-precision", R"({"choices":[]})", "application/json");
  ASSERT_TRUE(no_choice);
  EXPECT_EQ(no_choice->status, 400);
  EXPECT_EQ(json::parse(no_choice->body)["error"]["field"], "choices");
}

TEST_F(RenderCharts, ResidualsDrawEveryMethodAndDifferentialInBothPanels) {
  auto c = server.client();
  auto res = c.Post("/api/v1/render/residuals", R"({"problem":"paper-linear","n":5,"h":0.5,"width":1000,"height":480})",
                    "application/json");
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200) << res->body;
  const DecodedImage image = png_of(res);
  ASSERT_EQ(image.width, 1000);
  // 9 runs (fixed point once, two Newton versions x four differentials): 8 colours, the ninth repeats the first
  // with another dash and marker. The time panel (left 42%) shows every colour.
  EXPECT_EQ(series_colors(image, 0, 420).size(), 8u);
  EXPECT_EQ(series_colors(image, 420, image.width).size(), 8u);
  // Chosen lists: two runs.
  auto two = c.Get("/api/v1/render/residuals?n=4&h=0.5&methods=newton-group&differentials=exact,finite-difference");
  ASSERT_TRUE(two);
  ASSERT_EQ(two->status, 200) << two->body;
  EXPECT_EQ(series_colors(png_of(two), 0, 1200).size(), 2u);
  auto bad = c.Post("/api/v1/render/residuals", R"({"methods":["newton"]})", "application/json");
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->status, 400);
  EXPECT_EQ(json::parse(bad->body)["error"]["field"], "methods");
  auto single = c.Post("/api/v1/render/residuals", R"({"method":"newton-group"})", "application/json");
  ASSERT_TRUE(single);
  EXPECT_EQ(single->status, 400);
  EXPECT_EQ(json::parse(single->body)["error"]["field"], "method");
}

}  // namespace
}  // namespace lienewton::service
