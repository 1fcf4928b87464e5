#pragma once
// The render service's entry point: PNGs of rotation frames and of convergence heatmaps, drawn offscreen
// with OpenGL (OSMesa or EGL, see gl_context.hpp), or each picture as SVG (format svg, no GL needed).
#include <Eigen/Dense>
#include <functional>
#include <memory>
#include <vector>

#include "core/basins.hpp"
#include "core/groups/body_frame.hpp"
#include "core/sweep.hpp"
#include "render/camera.hpp"
#include "render/canvas.hpp"
#include "render/caption.hpp"
#include "render/figure.hpp"
#include "render/motion_scene.hpp"
#include "render/options.hpp"
#include "render/render_unavailable.hpp"

namespace lienewton::render {

// Thread-safe. Owns a small pool of long-lived GL contexts (one per worker); a call borrows one, waiting
// while all are busy. Contexts are created lazily: a creation failure throws RenderUnavailable from the call
// (the next call tries again). Width and height must be in [64, 4096] (heatmap: or 0 for automatic);
// otherwise std::invalid_argument names the field ("width"/"height").
class Renderer {
 public:
  // rasterizer_threads caps llvmpipe's threads per context (LP_NUM_THREADS, unless the environment sets it);
  // it takes effect only if this is the process' first renderer to create a context.
  explicit Renderer(int workers = 1, int rasterizer_threads = 1);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // frames: y_0, y_1, ... (iterates or a trajectory), the last drawn bold; start: the point z, dashed.
  std::vector<unsigned char> frames_png(const std::vector<Eigen::Matrix3d>& frames, const Eigen::Matrix3d& start,
                                        const FramesOptions& options, const Caption& caption = {},
                                        ImageFormat format = ImageFormat::png);
  // states: a system of bodies' frames, each state every body's (frames_scene.hpp's draw_bodies).
  std::vector<unsigned char> frames_png(const std::vector<std::vector<BodyFrame>>& states,
                                        const std::vector<BodyFrame>& start, const FramesOptions& options,
                                        const Caption& caption = {}, ImageFormat format = ImageFormat::png);
  // A motion (motion_scene.hpp) at state `at`, as PNG or SVG.
  std::vector<unsigned char> motion_png(const Motion& motion, std::size_t at, const FramesOptions& options,
                                        const Caption& caption = {}, ImageFormat format = ImageFormat::png);
  // The motion at the states `shown` in turn (each below times.size()), each shown frame_ms, as an animated WebP
  // (webp_animation.hpp) whose XMP metadata names each frame's time (lienewton:frameTimes, lienewton:timeName t or n).
  // Drawing stops, returning nothing, when keep_going(index into shown) says false. Throws
  // std::invalid_argument for frame_ms outside [1, 10000] or a state out of range.
  std::vector<unsigned char> motion_webp(const Motion& motion, const std::vector<std::size_t>& shown,
                                         const FramesOptions& options, const Caption& caption, int frame_ms,
                                         const std::function<bool(std::size_t)>& keep_going = {});
  // caption: a band above the picture (caption.hpp); a given height includes it.
  std::vector<unsigned char> heatmap_png(const lienewton::SweepResult& sweep, const HeatmapOptions& options,
                                         const Caption& caption = {}, ImageFormat format = ImageFormat::png);
  // Basin map (basin_scene.hpp); width/height 0 choose the size. Throws std::invalid_argument for an empty map.
  std::vector<unsigned char> basins_png(const lienewton::BasinResult& map, int width, int height,
                                        const Caption& caption = {}, ImageFormat format = ImageFormat::png);
  // Line-chart figures (work_precision_scene.hpp, residuals_scene.hpp); throws as layout_line_chart does.
  std::vector<unsigned char> figure_png(const Figure& figure, ImageFormat format = ImageFormat::png);

 private:
  // A scene under the orbit camera (the frames' pictures): options checked, caption band, drawn, encoded.
  std::vector<unsigned char> orbit_png(const FramesOptions& options, const Caption& caption, ImageFormat format,
                                       const std::function<void(Canvas&, const Camera&)>& draw);
  // The same scene as a canvas (options checked, caption band drawn).
  Canvas orbit_canvas(const FramesOptions& options, const Caption& caption,
                      const std::function<void(Canvas&, const Camera&)>& draw);
  class Pool;
  std::unique_ptr<Pool> pool_;
};

}  // namespace lienewton::render
