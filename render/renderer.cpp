#include "render/renderer.hpp"

#include <cmath>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <stdexcept>

#include "render/basin_scene.hpp"
#include "render/camera.hpp"
#include "render/frames_scene.hpp"
#include "render/gl_context.hpp"
#include "render/heatmap_scene.hpp"
#include "render/painter.hpp"
#include "render/png.hpp"

namespace lienewton::render {
namespace {

// A context and the GL objects made in it; the painter must die while its context is current.
struct Worker {
  GlContext context;
  std::optional<Painter> painter;

  Worker() {
    context.make_current();
    try {
      painter.emplace(context);
    } catch (...) {
      context.release();
      throw;
    }
    context.release();
  }
  ~Worker() {
    try {
      context.make_current();
      painter.reset();
      context.release();
    } catch (const RenderUnavailable&) {
      // Cannot bind it any more: the context's destruction frees its objects anyway.
    }
  }
};

}  // namespace

class Renderer::Pool {
 public:
  Pool(int workers, int rasterizer_threads) : rasterizer_threads_(rasterizer_threads), slots_(workers), busy_(workers) {}

  // Draws the canvas on a borrowed worker; RGB rows bottom-up.
  std::vector<std::uint8_t> paint(const Canvas& canvas) {
    const std::size_t slot = acquire();
    struct Return {
      Pool& pool;
      std::size_t slot;
      ~Return() { pool.give_back(slot); }
    } give_back_on_exit{*this, slot};
    std::unique_ptr<Worker>& worker = slots_[slot];
    try {
      if (!worker) {
        set_rasterizer_threads(rasterizer_threads_);
        worker = std::make_unique<Worker>();
      }
      worker->context.make_current();
      struct Release {
        GlContext& context;
        ~Release() { context.release(); }
      } release_on_exit{worker->context};
      return worker->painter->paint(canvas);
    } catch (const RenderUnavailable&) {
      worker.reset();  // a context that failed once is not trusted again; the next call makes a new one
      throw;
    }
  }

 private:
  std::size_t acquire() {
    std::unique_lock lock(mutex_);
    for (;;) {
      for (std::size_t i = 0; i < busy_.size(); ++i) {
        if (!busy_[i]) {
          busy_[i] = true;
          return i;
        }
      }
      freed_.wait(lock);
    }
  }
  void give_back(std::size_t slot) {
    {
      std::lock_guard lock(mutex_);
      busy_[slot] = false;
    }
    freed_.notify_one();
  }

  int rasterizer_threads_;
  std::mutex mutex_;
  std::condition_variable freed_;
  std::vector<std::unique_ptr<Worker>> slots_;  // each touched only by the thread that holds its busy flag
  std::vector<bool> busy_;
};

Renderer::Renderer(int workers, int rasterizer_threads) {
  if (workers < 1) throw std::invalid_argument("workers must be at least 1");
  pool_ = std::make_unique<Pool>(workers, rasterizer_threads);
}

Renderer::~Renderer() = default;

std::vector<unsigned char> Renderer::frames_png(const std::vector<Eigen::Matrix3d>& frames,
                                                const Eigen::Matrix3d& start, const FramesOptions& options) {
  validate_size("width", options.width, false);
  validate_size("height", options.height, false);
  if (!std::isfinite(options.azimuth_deg)) throw std::invalid_argument("azimuth_deg must be finite");
  if (!std::isfinite(options.elevation_deg)) throw std::invalid_argument("elevation_deg must be finite");
  // The scene is built before a worker is borrowed and encoded after it is returned: only drawing holds one.
  Canvas canvas(options.width, options.height, kWhite);
  draw_frames(canvas, Camera(options.azimuth_deg, options.elevation_deg, options.width, options.height), frames,
              start);
  const std::vector<std::uint8_t> rgb = pool_->paint(canvas);
  return encode_png(rgb, options.width, options.height, RowOrder::bottom_up);
}

std::vector<unsigned char> Renderer::heatmap_png(const lienewton::SweepResult& sweep, const HeatmapOptions& options) {
  validate_size("width", options.width, true);
  validate_size("height", options.height, true);
  const HeatmapGrid grid = make_grid(sweep);
  const HeatmapLayout layout = layout_heatmap(grid, options.metric, options.width, options.height);
  Canvas canvas(layout.width, layout.height, kWhite);
  draw_heatmap(canvas, grid, layout, options.metric);
  const std::vector<std::uint8_t> rgb = pool_->paint(canvas);
  return encode_png(rgb, layout.width, layout.height, RowOrder::bottom_up);
}

std::vector<unsigned char> Renderer::basins_png(const lienewton::BasinResult& map, int width, int height) {
  validate_size("width", width, true);
  validate_size("height", height, true);
  const BasinLayout layout = layout_basins(map, width, height);
  Canvas canvas(layout.width, layout.height, kWhite);
  draw_basin_decorations(canvas, map, layout);
  std::vector<std::uint8_t> rgb = pool_->paint(canvas);
  fill_basin_panels(rgb, map, layout);
  return encode_png(rgb, layout.width, layout.height, RowOrder::bottom_up);
}

std::vector<unsigned char> Renderer::figure_png(const Figure& figure) {
  validate_size("width", figure.width, false);
  validate_size("height", figure.height, false);
  Canvas canvas(figure.width, figure.height, kWhite);
  draw_figure(canvas, figure);
  const std::vector<std::uint8_t> rgb = pool_->paint(canvas);
  return encode_png(rgb, figure.width, figure.height, RowOrder::bottom_up);
}

}  // namespace lienewton::render
