// Renders per second at 512x512, each a full request: scene on the CPU, GL draw, read-back and PNG encode.
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

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

void BM_HeatmapPng512(benchmark::State& state) {
  const SweepResult sweep = default_grid();
  const render::HeatmapOptions options{512, 512, render::HeatmapMetric::iterations};
  if (!is_png(renderer().heatmap_png(sweep, options))) state.SkipWithError("heatmap_png returned no PNG");
  for (auto _ : state) benchmark::DoNotOptimize(renderer().heatmap_png(sweep, options));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_HeatmapPng512)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
