#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "png_decode.hpp"
#include "shared_renderer.hpp"
#include "render/caption.hpp"
#include "render/font.hpp"
#include "render/heatmap_scene.hpp"
#include "render/log_axis.hpp"
#include "render/renderer.hpp"

namespace lienewton::render {
namespace {

using testing::decode_png;
using testing::DecodedImage;

const Caption kCaption{"Where each method converges: paper-linear on SO(N)",
                       "N = 2\u20263 \u00b7 h = 2\u207b\u00b9\u20262 \u00b7 differential exact \u00b7 tol 1e-13 \u00b7 "
                       "at most 100 iterations \u00b7 colour: iterations"};

std::string joined(const std::vector<std::string>& lines, const std::string& separator) {
  std::string out;
  for (std::size_t i = 0; i < lines.size(); ++i) out += (i ? separator : "") + lines[i];
  return out;
}

TEST(Caption, WrapsTheSubtitleBetweenFactsOnlyWhereTheWidthIsShort) {
  const CaptionLines wide = caption_lines(kCaption, 2000);
  ASSERT_EQ(wide.title.size(), 1u);
  ASSERT_EQ(wide.subtitle.size(), 1u);
  EXPECT_EQ(wide.title[0], kCaption.title);
  EXPECT_EQ(wide.subtitle[0], kCaption.subtitle);
  const CaptionLines narrow = caption_lines(kCaption, 300);
  ASSERT_GT(narrow.subtitle.size(), 1u);
  EXPECT_EQ(joined(narrow.subtitle, " \u00b7 "), kCaption.subtitle);  // every fact kept, in order
  for (const std::string& line : narrow.subtitle) EXPECT_LE(Font::instance().width(line, TextSize::small), 280.0f) << line;
  EXPECT_GT(caption_height(kCaption, 300), caption_height(kCaption, 2000));
  EXPECT_EQ(caption_height(Caption{}, 500), 0);
}

// A title wider than a phone's picture is wrapped between words, none lost, each line within the picture.
TEST(Caption, WrapsALongTitleBetweenWords) {
  const CaptionLines narrow = caption_lines(kCaption, 240);
  ASSERT_GT(narrow.title.size(), 1u);
  EXPECT_EQ(joined(narrow.title, " "), kCaption.title);
  for (const std::string& line : narrow.title) EXPECT_LE(Font::instance().width(line, TextSize::large), 220.0f) << line;
  EXPECT_GT(caption_height(kCaption, 240), caption_height(kCaption, 300));
}

TEST(Caption, MicroSecondsAreSpelledWithMu) { EXPECT_TRUE(Font::instance().has_glyph(U'\u00b5')); }

TEST(Caption, StepSizesArePowersOfTwoWhereTheyAreOne) {
  EXPECT_EQ(power_of_two_label(0.125), "2\u207b\u00b3");
  EXPECT_EQ(power_of_two_label(1024), "2\u00b9\u2070");
  EXPECT_EQ(power_of_two_label(1), "2\u2070");
  EXPECT_EQ(power_of_two_label(0.3), "0.3");
  EXPECT_EQ(power_of_two_label(3), "3");
}

SweepResult small_sweep() {
  SweepResult sweep;
  for (int n : {2, 3}) {
    for (double h : {0.5, 1.0, 2.0}) {
      SweepCell c;
      c.method = Method::newton_group;
      c.n = n;
      c.h = h;
      c.status = Status::converged;
      c.iterations = n + static_cast<int>(2 * h);
      c.rate = 2.0;
      c.residual = 1e-14;
      sweep.cells.push_back(c);
    }
  }
  return sweep;
}

// The caption is a band of text above the heatmap, which is drawn below it unchanged: each cell's centre shows
// the colour it shows without a caption, moved down by the band.
TEST(Caption, HeatmapPngHasItsCaptionAboveTheUnchangedMap) {
  const SweepResult sweep = small_sweep();
  HeatmapOptions plain;
  plain.width = 400;
  const DecodedImage without = decode_png(testing::shared_renderer().heatmap_png(sweep, plain));
  const DecodedImage with = decode_png(testing::shared_renderer().heatmap_png(sweep, plain, kCaption));
  const int band = caption_height(kCaption, 400);
  ASSERT_GT(band, 0);
  ASSERT_EQ(with.width, without.width);
  ASSERT_EQ(with.height, without.height + band);
  EXPECT_GT(with.count_not(kWhite, 0, 0, with.width / 2, band), 200);  // the title's ink, at the left
  const HeatmapGrid grid = make_grid(sweep);
  const HeatmapLayout layout = layout_heatmap(grid, plain.metric, plain.width, plain.height);
  for (int i = 0; i < layout.rows; ++i) {
    for (int j = 0; j < layout.columns; ++j) {
      const Point c = layout.cell_center(0, i, j);
      const int x = static_cast<int>(c.x), y = static_cast<int>(c.y);
      EXPECT_TRUE(testing::near(with.at(x, y + band), without.at(x, y), 0)) << "cell " << i << ", " << j;
    }
  }
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// The SVG copy holds the same picture as vectors: its size, the caption's title as text, a rect per cell.
TEST(Caption, HeatmapSvgHasTheCaptionAsTextAndACellPerRect) {
  const SweepResult sweep = small_sweep();
  HeatmapOptions options;
  options.width = 400;
  const DecodedImage png = decode_png(testing::shared_renderer().heatmap_png(sweep, options, kCaption));
  const std::vector<unsigned char> bytes = testing::shared_renderer().heatmap_png(sweep, options, kCaption, ImageFormat::svg);
  const std::string svg(bytes.begin(), bytes.end());
  ASSERT_EQ(svg.rfind("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"400\" height=\"" + std::to_string(png.height) + "\"", 0), 0u)
      << svg.substr(0, 200);
  EXPECT_EQ(svg.substr(svg.size() - 7), "</svg>\n");
  EXPECT_NE(svg.find(">Where each method converges: paper-linear on SO(N)</text>"), std::string::npos);
  EXPECT_NE(svg.find("colour: iterations</text>"), std::string::npos);
  EXPECT_GE(count(svg, "<rect "), sweep.cells.size() + 1);
  EXPECT_EQ(count(svg, "<text "), count(svg, "</text>"));
}

// A frames picture keeps its requested size: the caption takes a band of it, the sphere and its legend the rest.
TEST(Caption, FramesPngKeepsItsSizeWithTheCaptionInsideIt) {
  const std::vector<Eigen::Matrix3d> frames{Eigen::Matrix3d::Identity()};
  FramesOptions options;
  options.width = options.height = 320;
  const Caption caption{"Iterates of Newton V1", "paper-linear on SO(3), h = 2\u207b\u00b9 \u00b7 tol 1e-13"};
  const DecodedImage with = decode_png(testing::shared_renderer().frames_png(frames, frames[0], options, caption));
  ASSERT_EQ(with.width, 320);
  ASSERT_EQ(with.height, 320);
  const int band = caption_height(caption, 320);
  EXPECT_GT(with.count_not(kWhite, 0, 0, 160, band), 100);
  EXPECT_GT(with.count_not(kWhite, 0, 320 - 50, 120, 320), 100);  // the legend, at the bottom left still
  const std::vector<unsigned char> bytes = testing::shared_renderer().frames_png(frames, frames[0], options, caption, ImageFormat::svg);
  EXPECT_NE(std::string(bytes.begin(), bytes.end()).find(">Iterates of Newton V1</text>"), std::string::npos);
}

// Every N gets a label when the height is automatic: the rows are at least a label tall.
TEST(Caption, AnAutomaticHeatmapLabelsEveryN) {
  SweepResult sweep;
  for (int n = 2; n <= 15; ++n) {
    for (int k = -10; k <= 10; ++k) {
      for (Method m : {Method::fixed_point, Method::newton_group, Method::newton_algebra}) {
        SweepCell c;
        c.method = m;
        c.n = n;
        c.h = std::ldexp(1.0, k);
        c.status = Status::diverged;
        sweep.cells.push_back(c);
      }
    }
  }
  const HeatmapGrid grid = make_grid(sweep);
  EXPECT_EQ(layout_heatmap(grid, HeatmapMetric::iterations, 0, 0).n_label_step, 1);
  EXPECT_EQ(layout_heatmap(grid, HeatmapMetric::iterations, 1200, 0).n_label_step, 1);
}

}  // namespace
}  // namespace lienewton::render
