#include "render/renderer.hpp"

#include <algorithm>
#include <charconv>
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
#include "render/webp_animation.hpp"
#include "render/png.hpp"
#include "render/svg.hpp"

namespace lienewton::render {
namespace {

// The animation's XMP packet: what its frames show (t or n) and the time of each, shortest round-trip decimals,
// so that a player's slider can name a frame's time however unevenly the frames were picked.
std::string frame_times_xmp(const Motion& motion, const std::vector<std::size_t>& shown) {
  std::string times;
  for (std::size_t at : shown) {
    char buffer[32];
    const auto end = std::to_chars(buffer, buffer + sizeof buffer, motion.times[at]).ptr;
    times.append(times.empty() ? "" : " ").append(buffer, end);
  }
  return "<x:xmpmeta xmlns:x=\"adobe:ns:meta/\"><rdf:RDF xmlns:rdf=\"http://www.w3.org/1999/02/22-rdf-syntax-ns#\">"
         "<rdf:Description rdf:about=\"\" xmlns:lienewton=\"urn:lienewton:motion:1\" lienewton:timeName=\"" +
         motion.time_name + "\" lienewton:frameTimes=\"" + times + "\"/></rdf:RDF></x:xmpmeta>";
}

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

std::vector<unsigned char> bytes_of(const std::string& text) { return {text.begin(), text.end()}; }

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
                                                const Eigen::Matrix3d& start, const FramesOptions& options,
                                                const Caption& caption, ImageFormat format) {
  return orbit_png(options, caption, format,
                   [&](Canvas& canvas, const Camera& camera) { draw_frames(canvas, camera, frames, start); });
}

std::vector<unsigned char> Renderer::frames_png(const std::vector<std::vector<BodyFrame>>& states,
                                                const std::vector<BodyFrame>& start, const FramesOptions& options,
                                                const Caption& caption, ImageFormat format) {
  return orbit_png(options, caption, format,
                   [&](Canvas& canvas, const Camera& camera) { draw_bodies(canvas, camera, states, start); });
}

Canvas Renderer::orbit_canvas(const FramesOptions& options, const Caption& caption,
                              const std::function<void(Canvas&, const Camera&)>& draw) {
  validate_size("width", options.width, false);
  validate_size("height", options.height, false);
  if (!std::isfinite(options.azimuth_deg)) throw std::invalid_argument("azimuth_deg must be finite");
  if (!std::isfinite(options.elevation_deg)) throw std::invalid_argument("elevation_deg must be finite");
  // The caption takes a band of the given height; the sphere keeps at least the smallest picture's room.
  const Caption shown = caption_height(caption, options.width) <= options.height - kMinImageSize ? caption : Caption{};
  Canvas canvas(options.width, options.height, kWhite);
  draw_caption(canvas, shown);
  draw(canvas, Camera(options.azimuth_deg, options.elevation_deg, options.width,
                      static_cast<int>(canvas.scene_height())));
  return canvas;
}

std::vector<unsigned char> Renderer::orbit_png(const FramesOptions& options, const Caption& caption,
                                               ImageFormat format,
                                               const std::function<void(Canvas&, const Camera&)>& draw) {
  // The scene is built before a worker is borrowed and encoded after it is returned: only drawing holds one.
  const Canvas canvas = orbit_canvas(options, caption, draw);
  if (format == ImageFormat::svg) return bytes_of(to_svg(canvas));
  const std::vector<std::uint8_t> rgb = pool_->paint(canvas);
  return encode_png(rgb, options.width, options.height, RowOrder::bottom_up);
}

std::vector<unsigned char> Renderer::motion_png(const Motion& motion, std::size_t at, const FramesOptions& options,
                                                const Caption& caption, ImageFormat format) {
  check_motion(motion);
  return orbit_png(options, caption, format,
                   [&](Canvas& canvas, const Camera& camera) { draw_motion(canvas, camera, motion, at); });
}

std::vector<unsigned char> Renderer::motion_webp(const Motion& motion, const std::vector<std::size_t>& shown,
                                                 const FramesOptions& options, const Caption& caption, int frame_ms,
                                                 const std::function<bool(std::size_t)>& keep_going) {
  if (frame_ms < 1 || frame_ms > 10000) throw std::invalid_argument("frame_ms must be in [1, 10000]");
  check_motion(motion);
  for (std::size_t at : shown)
    if (at >= motion.times.size()) throw std::invalid_argument("no such state");
  WebpAnimation animation(options.width, options.height);
  for (std::size_t i = 0; i < shown.size(); ++i) {
    if (keep_going && !keep_going(i)) return {};
    const Canvas canvas = orbit_canvas(
        options, caption, [&](Canvas& c, const Camera& camera) { draw_motion(c, camera, motion, shown[i]); });
    animation.add(pool_->paint(canvas), RowOrder::bottom_up, static_cast<int>(i) * frame_ms);
  }
  return animation.finish(static_cast<int>(shown.size()) * frame_ms, frame_times_xmp(motion, shown));
}

std::vector<unsigned char> Renderer::heatmap_png(const lienewton::SweepResult& sweep, const HeatmapOptions& options,
                                                 const Caption& caption, ImageFormat format) {
  validate_size("width", options.width, true);
  validate_size("height", options.height, true);
  const HeatmapGrid grid = make_grid(sweep);
  const int band = caption_height(caption, options.width == 0 ? 600 : options.width);
  const int height = options.height == 0 ? 0 : std::max(kMinImageSize, options.height - band);
  const HeatmapLayout layout = layout_heatmap(grid, options.metric, options.width, height);
  // An automatic width is known only now: the band for it.
  const int total = layout.height + caption_height(caption, layout.width);
  Canvas canvas(layout.width, total, kWhite);
  draw_caption(canvas, caption);
  draw_heatmap(canvas, grid, layout, options.metric);
  if (format == ImageFormat::svg) return bytes_of(to_svg(canvas));
  const std::vector<std::uint8_t> rgb = pool_->paint(canvas);
  return encode_png(rgb, layout.width, total, RowOrder::bottom_up);
}

std::vector<unsigned char> Renderer::basins_png(const lienewton::BasinResult& map, int width, int height,
                                                const Caption& caption, ImageFormat format) {
  validate_size("width", width, true);
  validate_size("height", height, true);
  const int band = caption_height(caption, width == 0 ? 600 : width);
  const BasinLayout layout = layout_basins(map, width, height == 0 ? 0 : std::max(kMinImageSize, height - band));
  const int total = layout.height + caption_height(caption, layout.width);
  Canvas canvas(layout.width, total, kWhite);
  draw_caption(canvas, caption);
  draw_basin_decorations(canvas, map, layout);
  // Rows bottom-up: the band is at the end, so the panels' rows count from the bottom as the layout's do.
  if (format == ImageFormat::png) {
    std::vector<std::uint8_t> rgb = pool_->paint(canvas);
    fill_basin_panels(rgb, map, layout);
    return encode_png(rgb, layout.width, total, RowOrder::bottom_up);
  }
  // SVG: the panels' pixels as one embedded PNG each, over the vector decorations' background.
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(layout.width) * total * 3, 255);
  fill_basin_panels(rgb, map, layout);
  std::vector<SvgImage> panels;
  const int size = layout.panel_size, top = total - layout.height + layout.top;
  for (int p = 0; p < layout.panels; ++p) {
    std::vector<std::uint8_t> crop;
    for (int y = top; y < top + size; ++y) {
      const auto* row = rgb.data() + (static_cast<std::size_t>(total - 1 - y) * layout.width + layout.panel_x(p)) * 3;
      crop.insert(crop.end(), row, row + static_cast<std::size_t>(size) * 3);
    }
    panels.push_back({static_cast<float>(layout.panel_x(p)), static_cast<float>(top), static_cast<float>(size),
                      static_cast<float>(size), encode_png(crop, size, size, RowOrder::top_down)});
  }
  return bytes_of(to_svg(canvas, panels));
}

std::vector<unsigned char> Renderer::figure_png(const Figure& figure, ImageFormat format) {
  validate_size("width", figure.width, false);
  validate_size("height", figure.height, false);
  Canvas canvas(figure.width, figure.height, kWhite);
  draw_figure(canvas, figure);
  if (format == ImageFormat::svg) return bytes_of(to_svg(canvas));
  const std::vector<std::uint8_t> rgb = pool_->paint(canvas);
  return encode_png(rgb, figure.width, figure.height, RowOrder::bottom_up);
}

}  // namespace lienewton::render
