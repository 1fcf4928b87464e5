// Renders per second at 512x512, each a full request: scene on the CPU, GL draw, read-back and PNG encode.
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "core/integrate.hpp"
#include "render/motion_of_problem.hpp"
#include "render/renderer.hpp"

namespace {

using lienewton::Method;
using lienewton::Status;
using lienewton::SweepCell;
using lienewton::SweepResult;
namespace render = lienewton::render;

// One renderer for all benchmarks: contexts are long-lived, as in the service, so JIT warm-up is not timed.
render::Renderer& renderer() {
  // Leaked on purpose: destroyed among the exit handlers, its contexts were made current after Mesa's own
  // teardown had run (SIGSEGV in OSMesaMakeCurrent at exit, seen when LargeN_Solve ran before BM_*).
  static render::Renderer& shared = *new render::Renderer(1);
  return shared;
}

bool is_png(const std::vector<unsigned char>& bytes) {
  static constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  return bytes.size() > 8 && std::equal(std::begin(kSignature), std::end(kSignature), bytes.begin());
}

// Twelve Newton iterates approaching a rotation from a start point.
std::vector<Eigen::Matrix3d> iterates() {
  const Eigen::Quaterniond start(Eigen::AngleAxisd(1.2, Eigen::Vector3d(1, 0.3, 0.2).normalized()));
  const Eigen::Quaterniond end(Eigen::AngleAxisd(0.4, Eigen::Vector3d(0.2, 1, 0.5).normalized()));
  std::vector<Eigen::Matrix3d> frames;
  for (int k = 0; k < 12; ++k) frames.push_back(start.slerp(1 - std::pow(0.4, k), end).toRotationMatrix());
  return frames;
}

// The paper's default grid: 3 methods x N = 2..15 x h = 2^-10..2^10, failing beyond a method-dependent h.
SweepResult default_grid() {
  SweepResult sweep;
  for (Method method : lienewton::kAllMethods) {
    for (int n = 2; n <= 15; ++n) {
      for (int e = -10; e <= 10; ++e) {
        SweepCell cell;
        cell.method = method;
        cell.n = n;
        cell.h = std::ldexp(1.0, e);
        cell.status = e > 2 * static_cast<int>(method) + n % 3 ? Status::max_iterations : Status::converged;
        cell.iterations = 3 + (e + 10) / 3;
        cell.rate = 1.0 + 0.05 * (e + 10);
        cell.residual = std::pow(10.0, -15 + 0.1 * (e + 10));
        sweep.cells.push_back(cell);
      }
    }
  }
  return sweep;
}

void BM_FramesPng512(benchmark::State& state) {
  const auto frames = iterates();
  const Eigen::Matrix3d start = frames.front();
  const render::FramesOptions options{512, 512, 35, 20};
  // The first call creates the context outside the timing and checks that a PNG comes out.
  if (!is_png(renderer().frames_png(frames, start, options))) state.SkipWithError("frames_png returned no PNG");
  for (auto _ : state) benchmark::DoNotOptimize(renderer().frames_png(frames, start, options));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_FramesPng512)->Unit(benchmark::kMillisecond)->UseRealTime();

// The heavy-top benchmark's motion over t = 0 ... 2, 1601 states (the path's samples), 201 of them shown.
struct HeavyTopMotion {
  render::Motion motion;
  std::vector<std::size_t> shown;
};
const HeavyTopMotion& heavy_top_motion() {
  static const HeavyTopMotion m = [] {
    lienewton::IntegrateRequest r;
    r.problem.kind = lienewton::ProblemKind::heavy_top;
    r.problem.group = "SOxR";
    r.integrator = lienewton::Integrator::rkmk_gauss2;
    r.t_end = 2;
    r.frames = 1000;
    r.reference = false;
    const lienewton::IntegrateResult result = lienewton::integrate(r);
    HeavyTopMotion out{render::motion_of(r.problem, result.frames, result.frame_times), {}};
    for (std::size_t i = 0; i <= 200; ++i) out.shown.push_back(i * (result.frames.size() - 1) / 200);
    return out;
  }();
  return m;
}

// One frame of the motion (the last state: the whole path drawn), drawn and encoded as the PNG still.
void BM_MotionFramePng512(benchmark::State& state) {
  const HeavyTopMotion& m = heavy_top_motion();
  const render::FramesOptions options{512, 512, 35, 20};
  const std::size_t last = m.motion.times.size() - 1;
  if (!is_png(renderer().motion_png(m.motion, last, options))) state.SkipWithError("motion_png returned no PNG");
  for (auto _ : state) benchmark::DoNotOptimize(renderer().motion_png(m.motion, last, options));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_MotionFramePng512)->Unit(benchmark::kMillisecond)->UseRealTime();

// The animation of 201 frames at 512x512 as one animated WebP.
void BM_MotionAnimation201Webp512(benchmark::State& state) {
  const HeavyTopMotion& m = heavy_top_motion();
  const render::FramesOptions options{512, 512, 35, 20};
  for (auto _ : state) benchmark::DoNotOptimize(renderer().motion_webp(m.motion, m.shown, options, {}, 50));
  state.SetItemsProcessed(state.iterations() * static_cast<long>(m.shown.size()));
}
BENCHMARK(BM_MotionAnimation201Webp512)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);

void BM_HeatmapPng512(benchmark::State& state) {
  const SweepResult sweep = default_grid();
  const render::HeatmapOptions options{512, 512, render::HeatmapMetric::iterations};
  if (!is_png(renderer().heatmap_png(sweep, options))) state.SkipWithError("heatmap_png returned no PNG");
  for (auto _ : state) benchmark::DoNotOptimize(renderer().heatmap_png(sweep, options));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_HeatmapPng512)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
