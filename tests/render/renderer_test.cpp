#include "render/renderer.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <thread>

#include "png_decode.hpp"

namespace lienewton::render {
namespace {

std::vector<Eigen::Matrix3d> some_iterates() {
  std::vector<Eigen::Matrix3d> frames;
  for (int k = 0; k < 5; ++k) {
    frames.push_back(Eigen::AngleAxisd(0.3 * k, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix());
  }
  return frames;
}

SweepResult small_sweep() {
  SweepResult sweep;
  for (Method m : kAllMethods) {
    for (int n = 2; n <= 4; ++n) {
      for (int e = -2; e <= 2; ++e) {
        SweepCell c;
        c.method = m;
        c.n = n;
        c.h = std::ldexp(1.0, e);
        c.status = e == 2 ? Status::stagnated : Status::converged;
        c.iterations = 2 + n + e + 2;
        c.rate = 1.5 + 0.1 * n;
        c.residual = 1e-14;
        sweep.cells.push_back(c);
      }
    }
  }
  return sweep;
}

TEST(Renderer, FramesPngHasTheRequestedSize) {
  Renderer renderer;
  const auto image = testing::decode_png(renderer.frames_png(some_iterates(), Eigen::Matrix3d::Identity(),
                                                             {640, 360, 35, 20}));
  EXPECT_EQ(image.width, 640);
  EXPECT_EQ(image.height, 360);
}

TEST(Renderer, SameRequestGivesTheSameBytes) {
  Renderer renderer;
  const FramesOptions frames_options{};
  const auto a = renderer.frames_png(some_iterates(), Eigen::Matrix3d::Identity(), frames_options);
  const auto h = renderer.heatmap_png(small_sweep(), {});
  const auto b = renderer.frames_png(some_iterates(), Eigen::Matrix3d::Identity(), frames_options);
  EXPECT_EQ(a, b);
  EXPECT_EQ(h, renderer.heatmap_png(small_sweep(), {}));
  EXPECT_NE(a, h);
}

TEST(Renderer, InvalidSizesThrowNamingTheFieldAndRenderingGoesOn) {
  Renderer renderer;
  const auto frames = some_iterates();
  const Eigen::Matrix3d start = Eigen::Matrix3d::Identity();
  auto message_of = [](auto&& call) -> std::string {
    try {
      call();
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "no exception";
  };
  EXPECT_NE(message_of([&] { renderer.frames_png(frames, start, {63, 512, 0, 0}); }).find("width"), std::string::npos);
  EXPECT_NE(message_of([&] { renderer.frames_png(frames, start, {512, 4097, 0, 0}); }).find("height"),
            std::string::npos);
  EXPECT_NE(message_of([&] { renderer.frames_png(frames, start, {0, 512, 0, 0}); }).find("width"), std::string::npos);
  EXPECT_NE(message_of([&] { renderer.heatmap_png(small_sweep(), {-1, 0, HeatmapMetric::rate}); }).find("width"),
            std::string::npos);
  EXPECT_NE(message_of([&] { renderer.heatmap_png(small_sweep(), {0, 10, HeatmapMetric::rate}); }).find("height"),
            std::string::npos);
  const auto image = testing::decode_png(renderer.frames_png(frames, start, {64, 4096, 0, 0}));
  EXPECT_EQ(image.width, 64);
  EXPECT_EQ(image.height, 4096);
  EXPECT_EQ(testing::decode_png(renderer.heatmap_png(small_sweep(), {64, 64, HeatmapMetric::rate})).width, 64);
}

TEST(Renderer, ConcurrentRendersGiveIdenticalBytes) {
  Renderer renderer(2);
  const auto frames = some_iterates();
  const Eigen::Matrix3d start = Eigen::Matrix3d::Identity();
  const auto expected_frames = renderer.frames_png(frames, start, {});
  const auto expected_heatmap = renderer.heatmap_png(small_sweep(), {});
  std::vector<std::vector<unsigned char>> results[2];
  auto work = [&](int t) {
    for (int k = 0; k < 4; ++k) {
      results[t].push_back(renderer.frames_png(frames, start, {}));
      results[t].push_back(renderer.heatmap_png(small_sweep(), {}));
    }
  };
  std::thread first(work, 0), second(work, 1);
  first.join();
  second.join();
  for (const auto& result : results) {
    ASSERT_EQ(result.size(), 8u);
    for (std::size_t k = 0; k < result.size(); ++k) EXPECT_EQ(result[k], k % 2 ? expected_heatmap : expected_frames);
  }
}

TEST(Renderer, AtLeastOneWorker) { EXPECT_THROW(Renderer(0), std::invalid_argument); }

}  // namespace
}  // namespace lienewton::render
