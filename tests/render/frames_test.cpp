#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "png_decode.hpp"
#include "shared_renderer.hpp"
#include "render/camera.hpp"
#include "render/frames_scene.hpp"
#include "render/renderer.hpp"

namespace lienewton::render {
namespace {

using testing::decode_png;
using testing::DecodedImage;

// The pixel containing a point of the canvas.
Color pixel_at(const DecodedImage& image, Point p) { return image.at(static_cast<int>(p.x), static_cast<int>(p.y)); }

// Pixels along the projected body axis (skipping the middle, where the axes meet, and the tip label).
void expect_axis_drawn(const DecodedImage& image, const Camera& camera, const Eigen::Vector3d& axis, Color color) {
  for (double t : {0.3, 0.5, 0.7, 0.9}) {
    const Point p = camera.project(t * axis);
    EXPECT_TRUE(testing::near(pixel_at(image, p), color, 2))
        << "at t = " << t << " (" << p.x << ", " << p.y << ")";
  }
}

TEST(FramesScene, IdentityFrontViewPutsXRightYUp) {
  const FramesOptions options{512, 512, 0, 0};
  const DecodedImage image = decode_png(
      testing::shared_renderer().frames_png({Eigen::Matrix3d::Identity()}, Eigen::Matrix3d::Identity(), options));
  ASSERT_EQ(image.width, 512);
  ASSERT_EQ(image.height, 512);
  const Camera camera(0, 0, 512, 512);
  const Point x_tip = camera.project(Eigen::Vector3d::UnitX());
  const Point y_tip = camera.project(Eigen::Vector3d::UnitY());
  EXPECT_GT(x_tip.x, 256 + 150);  // right of centre
  EXPECT_FLOAT_EQ(x_tip.y, 256);
  EXPECT_LT(y_tip.y, 256 - 150);  // above centre
  expect_axis_drawn(image, camera, Eigen::Vector3d::UnitX(), kAxisColors[0]);
  expect_axis_drawn(image, camera, Eigen::Vector3d::UnitY(), kAxisColors[1]);
  // Nothing red left of the centre, nothing green below it.
  const Color left = pixel_at(image, camera.project(-0.5 * Eigen::Vector3d::UnitX()));
  const Color below = pixel_at(image, camera.project(-0.5 * Eigen::Vector3d::UnitY()));
  EXPECT_FALSE(testing::near(left, kAxisColors[0], 60));
  EXPECT_FALSE(testing::near(below, kAxisColors[1], 60));
}

TEST(FramesScene, AzimuthNinetyLooksDownTheXAxis) {
  // The camera swings from +z to +x: world z then points left on screen, y still up.
  const FramesOptions options{300, 200, 90, 0};
  const DecodedImage image =
      decode_png(testing::shared_renderer().frames_png({Eigen::Matrix3d::Identity()}, Eigen::Matrix3d::Identity(), options));
  ASSERT_EQ(image.width, 300);
  ASSERT_EQ(image.height, 200);
  const Camera camera(90, 0, 300, 200);
  EXPECT_LT(camera.project(Eigen::Vector3d::UnitZ()).x, 150 - 50);
  expect_axis_drawn(image, camera, Eigen::Vector3d::UnitZ(), kAxisColors[2]);
  expect_axis_drawn(image, camera, Eigen::Vector3d::UnitY(), kAxisColors[1]);
}

TEST(FramesScene, LastFrameIsBoldAndEarlierOnesFaded) {
  // Two frames: a quarter turn about z, then the identity (last). The earlier frame's x axis points up.
  const Eigen::Matrix3d quarter = Eigen::AngleAxisd(EIGEN_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Matrix3d start = Eigen::AngleAxisd(-EIGEN_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const FramesOptions options{400, 400, 0, 0};
  const DecodedImage image = decode_png(testing::shared_renderer().frames_png({quarter, Eigen::Matrix3d::Identity()}, start, options));
  const Camera camera(0, 0, 400, 400);
  expect_axis_drawn(image, camera, Eigen::Vector3d::UnitX(), kAxisColors[0]);
  // Bold: the last frame's axis covers the rows next to its centre line too.
  const Point mid = camera.project(0.6 * Eigen::Vector3d::UnitX());
  EXPECT_TRUE(testing::near(image.at(int(mid.x), int(mid.y) - 1), kAxisColors[0], 2));
  EXPECT_TRUE(testing::near(image.at(int(mid.x), int(mid.y) + 1), kAxisColors[0], 2));
  // Faded: the earlier frame's y axis points left (world -x), green but lighter than the bold green.
  const Color faded = pixel_at(image, camera.project(-0.6 * Eigen::Vector3d::UnitX()));
  EXPECT_GT(faded.g, faded.r);
  EXPECT_GT(faded.g, faded.b);
  EXPECT_GT(faded.r, kAxisColors[1].r + 40);
  EXPECT_LT(faded.r, 250);
  // The start's x axis points down (world -y): dashed, so along it some pixels are red-ish and some are not.
  int reddish = 0, other = 0;
  for (int k = 0; k < 60; ++k) {
    const Point p = camera.project((0.25 + 0.01 * k) * -Eigen::Vector3d::UnitY());
    const Color c = pixel_at(image, p);
    (c.r > 150 && c.g < 120 && c.b < 120 ? reddish : other) += 1;
  }
  EXPECT_GT(reddish, 10);
  EXPECT_GT(other, 10);
}

TEST(FramesScene, NonRotationsAreRejected) {
  Eigen::Matrix3d nan = Eigen::Matrix3d::Identity();
  nan(1, 2) = std::numeric_limits<double>::quiet_NaN();
  const Eigen::Matrix3d huge = 1e300 * Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d id = Eigen::Matrix3d::Identity();
  EXPECT_THROW(testing::shared_renderer().frames_png({nan}, id, FramesOptions{}), std::invalid_argument);
  EXPECT_THROW(testing::shared_renderer().frames_png({id}, huge, FramesOptions{}), std::invalid_argument);
}

// Three bodies hanging below the origin along -z, front view with z up: each body's x axis is drawn in red at its
// position, the chain between them in gray, and the scene is fitted into the picture (the lowest body inside it).
// The scene's coordinates (camera's y up) are the world's turned: (x, y, z) -> (x, z, -y).
TEST(FramesScene, BodiesAreTheirAxesAtTheirPositions) {
  std::vector<BodyFrame> chain;
  for (int i = 1; i <= 3; ++i) chain.push_back({Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, -0.5 * i)});
  const FramesOptions options{400, 400, 0, 0};
  const DecodedImage image = decode_png(testing::shared_renderer().frames_png({chain}, chain, options));
  const Camera camera(0, 0, 400, 400);
  // The fit: the box from the origin to the lowest body, centred, its half-diagonal 0.85 of the unit sphere's place.
  const auto at = [](const Eigen::Vector3d& p) -> Eigen::Vector3d {
    return (0.85 / 0.75) * (p - Eigen::Vector3d(0, -0.75, 0));
  };
  for (const BodyFrame& body : chain) {
    const Eigen::Vector3d scene(body.position.x(), body.position.z(), -body.position.y());
    const Point red = camera.project(at(scene + Eigen::Vector3d(0.08, 0, 0)));
    EXPECT_TRUE(testing::near(pixel_at(image, red), kAxisColors[0], 2)) << "body at " << body.position.z();
    EXPECT_GT(red.y, 0);
    EXPECT_LT(red.y, 400);
  }
  const Color link = pixel_at(image, camera.project(at(Eigen::Vector3d(0, -0.75, 0))));
  EXPECT_TRUE(testing::near(link, Color{110, 110, 110, 255}, 30)) << int(link.r) << " " << int(link.g);
  EXPECT_THROW(testing::shared_renderer().frames_png({chain, {chain.front()}}, chain, options), std::invalid_argument);
}

}  // namespace
}  // namespace lienewton::render
