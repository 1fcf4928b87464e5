#pragma once
// The GL side of a render worker: one shader program, one vertex buffer, the glyph atlas texture and an
// offscreen framebuffer, created once per context and reused for every picture.
#include <cstdint>
#include <vector>

#include "render/canvas.hpp"
#include "render/gl_functions.hpp"

namespace lienewton::render {

class Painter {
 public:
  // The context must be current on the calling thread, here and in every call.
  explicit Painter(const GlContext& context);
  ~Painter();
  Painter(const Painter&) = delete;
  Painter& operator=(const Painter&) = delete;

  // Draws the canvas and reads it back: RGB, 3 bytes per pixel, rows bottom-up as GL stores them.
  // Throws RenderUnavailable on a GL error.
  std::vector<std::uint8_t> paint(const Canvas& canvas);

 private:
  void resize(int width, int height);
  void check(const char* what);

  GlFunctions gl_;
  GLuint program_ = 0;
  GLuint vertex_array_ = 0;
  GLuint vertex_buffer_ = 0;
  GLuint atlas_ = 0;
  GLuint framebuffer_ = 0;
  GLuint color_buffer_ = 0;
  GLint size_uniform_ = -1;
  int width_ = 0;
  int height_ = 0;
};

}  // namespace lienewton::render
