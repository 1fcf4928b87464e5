#include <gtest/gtest.h>
#include <webp/demux.h>

#include <Eigen/Geometry>
#include <cmath>
#include <set>
#include <sstream>
#include <utility>

#include "core/integrate.hpp"
#include "png_decode.hpp"
#include "render/colormap.hpp"
#include "render/motion_of_problem.hpp"
#include "render/solid.hpp"
#include "shared_renderer.hpp"

namespace lienewton::render {
namespace {

using testing::decode_png;
using testing::DecodedImage;
using testing::shared_renderer;

TEST(Solid, EllipsoidMeshIsClosedOutwardAndOnItsSurface) {
  const Eigen::Vector3d axes(0.7, 0.3, 1.9);
  const Mesh mesh = ellipsoid_mesh(axes, 20);
  // Every directed edge once, and its reverse once: a closed, consistently oriented surface of genus 0.
  std::set<std::pair<int, int>> edges;
  for (const auto& [a, b, c] : mesh.faces)
    for (const auto& e : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}}) EXPECT_TRUE(edges.insert(e).second);
  for (const auto& [a, b] : edges) EXPECT_TRUE(edges.count({b, a})) << a << "-" << b;
  const long v = long(mesh.vertices.size()), e = long(edges.size()) / 2, f = long(mesh.faces.size());
  EXPECT_EQ(v - e + f, 2);
  for (const Eigen::Vector3d& x : mesh.vertices) EXPECT_NEAR(x.cwiseQuotient(axes).squaredNorm(), 1.0, 1e-12);
  for (const auto& [a, b, c] : mesh.faces) {
    const Eigen::Vector3d& p = mesh.vertices[a];
    const Eigen::Vector3d normal = (mesh.vertices[b] - p).cross(mesh.vertices[c] - p);
    EXPECT_GT(normal.dot(p + mesh.vertices[b] + mesh.vertices[c]), 0);  // outward: the centre is behind every face
  }
}

TEST(Solid, InertiaEllipsoidHasTheInertiaItWasGiven) {
  // A uniform ellipsoid of mass m and semi-axes a, b, c has I_1 = m (b^2 + c^2) / 5 and its turns.
  const Eigen::Vector3d inertia(1.0, 2.0, 2.5);
  const double mass = 3.0;
  const Eigen::Vector3d s = inertia_ellipsoid(inertia, mass).cwiseAbs2();
  EXPECT_NEAR(mass * (s[1] + s[2]) / 5, inertia[0], 1e-12);
  EXPECT_NEAR(mass * (s[0] + s[2]) / 5, inertia[1], 1e-12);
  EXPECT_NEAR(mass * (s[0] + s[1]) / 5, inertia[2], 1e-12);
  // The benchmark's top is a thin disc (I_2 = I_1 + I_3): its thickness is kept at 8% of its radius, which is
  // sqrt(5 I_2 / (2 m)).
  const Eigen::Vector3d disc = inertia_ellipsoid({0.234375, 0.46875, 0.234375}, 15.0);
  const double radius = std::sqrt(5 * 0.46875 / 30);
  EXPECT_NEAR(disc[0], radius, 1e-12);
  EXPECT_NEAR(disc[2], radius, 1e-12);
  EXPECT_NEAR(disc[1], 0.08 * radius, 1e-12);
}

TEST(EnergyCurves, LieOnTheSphereAtTheirLevels) {
  const Eigen::Vector3d inertia(1.0, 2.0, 3.0);
  const double radius = 1.3;
  const Eigen::Vector3d m0 = radius * Eigen::Vector3d(0.6, 0.8, 0.5).normalized();
  const auto energy = [&](const Eigen::Vector3d& x) { return 0.5 * x.dot(x.cwiseQuotient(inertia)); };
  const double own = energy(m0);
  const auto curves = energy_curves(inertia, radius, 5, own);
  ASSERT_FALSE(curves.empty());
  const double least = 0.5 * radius * radius / 3, most = 0.5 * radius * radius / 1;
  std::vector<double> levels{own, 0.5 * radius * radius / 2};
  for (int i = 1; i <= 5; ++i) levels.push_back(least + (most - least) * i / 6);
  double nearest_to_start = 1e300;
  for (const auto& segment : curves) {
    for (const Eigen::Vector3d& x : segment) {
      EXPECT_NEAR(x.norm(), radius, 1e-12);
      double gap = 1e300;
      for (double e : levels) gap = std::min(gap, std::abs(energy(x) - e));
      // Crossings interpolated on a 96 x 48 grid: within a few thousandths of the energy range of a level.
      EXPECT_LT(gap, 3e-3 * (most - least));
      if (std::abs(energy(x) - own) < 3e-3 * (most - least)) nearest_to_start = std::min(nearest_to_start, (x - m0).norm());
    }
  }
  EXPECT_LT(nearest_to_start, 0.05 * radius);  // the start's own level passes through the start
}

IntegrateRequest rigid_body_run(int frames) {
  IntegrateRequest r;
  r.problem.kind = ProblemKind::rigid_body;
  r.integrator = Integrator::rkmk_gauss2;
  r.h = 1.0 / 64;
  r.t_end = 4.0;
  r.frames = frames;
  r.reference = false;
  return r;
}

TEST(MotionOfProblem, RigidBodyMomentumStaysOnItsSphereAndItsDrawnLevel) {
  const IntegrateRequest r = rigid_body_run(40);
  const IntegrateResult result = integrate(r);
  const Motion m = motion_of(r.problem, result.frames, result.frame_times);
  ASSERT_EQ(m.trace.size(), result.frames.size());
  ASSERT_TRUE(m.sphere);
  const Eigen::Vector3d& inertia = r.problem.rigid_body.inertia;
  const auto energy = [&](const Eigen::Vector3d& x) { return 0.5 * x.dot(x.cwiseQuotient(inertia)); };
  for (const Eigen::Vector3d& x : m.trace) {
    EXPECT_NEAR(x.norm(), *m.sphere, 1e-12);  // y(t) is a rotation: |y^T m| = |m|
    // Gauss2 (order 4) conserves the energy to its truncation: the path stays on the level it starts on.
    EXPECT_NEAR(energy(x), energy(m.trace.front()), 1e-7);
  }
  // The start's M = y(0)^T m, independently.
  EXPECT_LT((m.trace.front() - result.frames.front().transpose() * r.problem.rigid_body.momentum).norm(), 1e-15);
}

IntegrateRequest heavy_top_run(double h, double t_end, int frames) {
  IntegrateRequest r;
  r.problem.kind = ProblemKind::heavy_top;
  r.problem.group = "SOxR";
  r.integrator = Integrator::rkmk_gauss2;
  r.h = h;
  r.t_end = t_end;
  r.frames = frames;
  r.reference = false;
  return r;
}

TEST(MotionOfProblem, HeavyTopTracesAPointFixedInTheBodyAtTheDiscsAxis) {
  const IntegrateRequest r = heavy_top_run(1.0 / 2048, 0.05, 20);
  const IntegrateResult result = integrate(r);
  ASSERT_EQ(result.status, Status::converged) << result.reason;
  const Motion m = motion_of(r.problem, result.frames, result.frame_times);
  ASSERT_EQ(m.bodies.size(), 2u);  // the disc and the rod, turning together about the pivot
  ASSERT_TRUE(m.gravity && m.pivot);
  // The tip is rigid in the body: its distance from the pivot never changes, and it lies on the symmetry axis chi.
  const Eigen::Vector3d chi = r.problem.heavy_top.center;
  for (std::size_t i = 0; i < m.trace.size(); ++i) {
    EXPECT_NEAR(m.trace[i].norm(), m.trace.front().norm(), 1e-12);
    const Eigen::Vector3d in_body = m.bodies.front().rotation[i].transpose() * m.trace[i];
    EXPECT_LT(in_body.cross(chi).norm(), 1e-12 * in_body.norm());
    EXPECT_GT(in_body.norm(), chi.norm());  // beyond the centre, where the axis leaves the disc
  }
}

std::vector<std::size_t> all_states(const Motion& m) {
  std::vector<std::size_t> out(m.times.size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = i;
  return out;
}

bool bluish(Color c) { return c.b > c.r + 40 && c.b > c.g + 10; }

TEST(MotionScene, StillShowsTheBodyAndThePathInTimeColours) {
  const IntegrateRequest r = heavy_top_run(1.0 / 1024, 0.1, 30);
  const IntegrateResult result = integrate(r);
  const Motion m = motion_of(r.problem, result.frames, result.frame_times);
  const DecodedImage image = decode_png(shared_renderer().motion_png(m, m.times.size() - 1, FramesOptions{}));
  ASSERT_EQ(image.width, 512);
  int body = 0, late = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const Color c = image.at(x, y);
      body += bluish(c);
      late += testing::near(c, viridis(1.0), 25);
    }
  EXPECT_GT(body, 2000);  // the disc, flat shaded in the body's blue
  EXPECT_GT(late, 20);    // the path's last segments (and the colour key's end) in viridis' yellow
}

TEST(MotionScene, AnimationFramesAreTheStillsOneByOne) {
  const IntegrateResult result = integrate(rigid_body_run(7));
  const Motion m = motion_of(rigid_body_run(7).problem, result.frames, result.frame_times);
  const FramesOptions options{200, 160, 35, 20};
  const std::vector<unsigned char> webp = shared_renderer().motion_webp(m, all_states(m), options, {}, 40);
  WebPData data{webp.data(), webp.size()};
  WebPAnimDecoderOptions decoder_options;
  ASSERT_TRUE(WebPAnimDecoderOptionsInit(&decoder_options));
  decoder_options.color_mode = MODE_RGBA;
  WebPAnimDecoder* decoder = WebPAnimDecoderNew(&data, &decoder_options);
  ASSERT_NE(decoder, nullptr);
  WebPAnimInfo info;
  ASSERT_TRUE(WebPAnimDecoderGetInfo(decoder, &info));
  EXPECT_EQ(info.canvas_width, 200u);
  EXPECT_EQ(info.canvas_height, 160u);
  EXPECT_EQ(info.frame_count, m.times.size());
  EXPECT_EQ(info.loop_count, 0u);
  std::size_t index = 0;
  while (WebPAnimDecoderHasMoreFrames(decoder)) {
    std::uint8_t* rgba = nullptr;
    int timestamp = 0;
    ASSERT_TRUE(WebPAnimDecoderGetNext(decoder, &rgba, &timestamp));
    EXPECT_EQ(timestamp, 40 * static_cast<int>(index + 1));  // a frame's end time
    // Lossless: each frame is exactly the still of its state.
    const DecodedImage still = decode_png(shared_renderer().motion_png(m, index, options));
    int differing = 0;
    for (int i = 0; i < 200 * 160; ++i)
      for (int k = 0; k < 3; ++k) differing += rgba[4 * i + k] != still.rgb[3 * i + k];
    EXPECT_EQ(differing, 0) << "frame " << index;
    ++index;
  }
  EXPECT_EQ(index, m.times.size());
  WebPAnimDecoderDelete(decoder);
}

// The XMP packet names each shown frame's time, exactly (shortest round trip), in the order shown.
TEST(MotionScene, AnimationNamesTheTimeOfEachFrame) {
  const IntegrateResult result = integrate(rigid_body_run(7));
  Motion m = motion_of(rigid_body_run(7).problem, result.frames, result.frame_times);
  const std::vector<std::size_t> shown{0, 3, 4, m.times.size() - 1};
  const std::vector<unsigned char> webp = shared_renderer().motion_webp(m, shown, FramesOptions{96, 96, 35, 20}, {}, 40);
  WebPData data{webp.data(), webp.size()};
  WebPDemuxer* demux = WebPDemux(&data);
  ASSERT_NE(demux, nullptr);
  EXPECT_TRUE(WebPDemuxGetI(demux, WEBP_FF_FORMAT_FLAGS) & XMP_FLAG);
  EXPECT_EQ(WebPDemuxGetI(demux, WEBP_FF_FRAME_COUNT), shown.size());
  WebPChunkIterator chunk;
  ASSERT_TRUE(WebPDemuxGetChunk(demux, "XMP ", 1, &chunk));
  const std::string xmp(reinterpret_cast<const char*>(chunk.chunk.bytes), chunk.chunk.size);
  WebPDemuxReleaseChunkIterator(&chunk);
  WebPDemuxDelete(demux);
  EXPECT_NE(xmp.find("lienewton:timeName=\"t\""), std::string::npos);
  const std::size_t from = xmp.find("lienewton:frameTimes=\"");
  ASSERT_NE(from, std::string::npos);
  std::istringstream times(xmp.substr(from + 22, xmp.find('"', from + 22) - from - 22));
  std::vector<double> read;
  for (double t; times >> t;) read.push_back(t);
  ASSERT_EQ(read.size(), shown.size());
  for (std::size_t i = 0; i < shown.size(); ++i) EXPECT_EQ(read[i], m.times[shown[i]]) << i;
  EXPECT_GT(read.back(), read.front());
}

TEST(MotionScene, RefusesWhatItCannotDraw) {
  Motion m;
  EXPECT_THROW(check_motion(m), std::invalid_argument);  // no state
  m.times = {0.0, 1.0};
  m.trace = {Eigen::Vector3d::Zero()};
  EXPECT_THROW(check_motion(m), std::invalid_argument);  // a point short
  m.trace.push_back(Eigen::Vector3d(std::nan(""), 0, 0));
  EXPECT_THROW(check_motion(m), std::invalid_argument);
  m.trace.back() = Eigen::Vector3d(1, 0, 0);
  EXPECT_NO_THROW(check_motion(m));
  m.bodies.emplace_back();
  EXPECT_THROW(check_motion(m), std::invalid_argument);  // no mesh 0
  Motion one;
  one.times = {0.0};
  EXPECT_THROW(shared_renderer().motion_webp(one, {0}, FramesOptions{}, {}, 0), std::invalid_argument);
  EXPECT_THROW(shared_renderer().motion_webp(one, {1}, FramesOptions{}, {}, 40), std::invalid_argument);
}

}  // namespace
}  // namespace lienewton::render
