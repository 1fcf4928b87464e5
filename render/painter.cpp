#include "render/painter.hpp"

#include <cstddef>
#include <string>

#include "render/gl_context.hpp"
#include "render/render_unavailable.hpp"

namespace lienewton::render {
namespace {

constexpr const char* kVertexShader = R"(#version 330 core
layout(location = 0) in vec2 a_pos;
layout(location = 1) in vec2 a_uv;
layout(location = 2) in vec4 a_color;
layout(location = 3) in vec4 a_segment;
layout(location = 4) in float a_half_width;
uniform vec2 u_size;
out vec2 v_pos;
out vec2 v_uv;
flat out vec4 v_color;
flat out vec4 v_segment;
flat out float v_half_width;
void main() {
  v_pos = a_pos;
  v_uv = a_uv;
  v_color = a_color;
  v_segment = a_segment;
  v_half_width = a_half_width;
  // top-down pixels to clip space; GL's row 0 is then the picture's bottom row
  gl_Position = vec4(a_pos.x / u_size.x * 2.0 - 1.0, 1.0 - a_pos.y / u_size.y * 2.0, 0.0, 1.0);
}
)";

constexpr const char* kFragmentShader = R"(#version 330 core
uniform sampler2D u_atlas;
in vec2 v_pos;
in vec2 v_uv;
flat in vec4 v_color;
flat in vec4 v_segment;
flat in float v_half_width;
out vec4 o_color;
void main() {
  float coverage;
  if (v_half_width > 0.0) {
    // distance from the pixel centre to the segment: a capsule with a one-pixel soft edge
    vec2 ab = v_segment.zw - v_segment.xy;
    vec2 ap = v_pos - v_segment.xy;
    float len2 = dot(ab, ab);
    float t = len2 > 0.0 ? clamp(dot(ap, ab) / len2, 0.0, 1.0) : 0.0;
    coverage = clamp(v_half_width + 0.5 - length(ap - t * ab), 0.0, 1.0);
  } else {
    coverage = texture(u_atlas, v_uv).r;
  }
  o_color = vec4(v_color.rgb, v_color.a * coverage);
}
)";

// Throws with GL's info log when a compile or link step failed.
template <class GetLog>
void require_ok(GLint ok, const char* what, GetLog get_log) {
  if (ok) return;
  char log[1024] = {};
  get_log(log, static_cast<GLsizei>(sizeof log));
  throw RenderUnavailable(std::string(what) + ": " + log);
}

}  // namespace

Painter::Painter(const GlContext& context) : gl_(load_gl_functions(context)) {
  auto compile = [this](GLenum type, const char* source) {
    const GLuint shader = gl_.CreateShader(type);
    gl_.ShaderSource(shader, 1, &source, nullptr);
    gl_.CompileShader(shader);
    GLint ok = 0;
    gl_.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    require_ok(ok, "shader does not compile",
               [&](char* log, GLsizei size) { gl_.GetShaderInfoLog(shader, size, nullptr, log); });
    return shader;
  };
  const GLuint vertex = compile(GL_VERTEX_SHADER, kVertexShader);
  const GLuint fragment = compile(GL_FRAGMENT_SHADER, kFragmentShader);
  program_ = gl_.CreateProgram();
  gl_.AttachShader(program_, vertex);
  gl_.AttachShader(program_, fragment);
  gl_.LinkProgram(program_);
  gl_.DeleteShader(vertex);
  gl_.DeleteShader(fragment);
  GLint linked = 0;
  gl_.GetProgramiv(program_, GL_LINK_STATUS, &linked);
  require_ok(linked, "shader program does not link",
             [&](char* log, GLsizei size) { gl_.GetProgramInfoLog(program_, size, nullptr, log); });
  gl_.UseProgram(program_);
  size_uniform_ = gl_.GetUniformLocation(program_, "u_size");
  gl_.Uniform1i(gl_.GetUniformLocation(program_, "u_atlas"), 0);

  gl_.GenVertexArrays(1, &vertex_array_);
  gl_.BindVertexArray(vertex_array_);
  gl_.GenBuffers(1, &vertex_buffer_);
  gl_.BindBuffer(GL_ARRAY_BUFFER, vertex_buffer_);
  auto attribute = [this](GLuint index, GLint count, GLenum type, GLboolean normalized, std::size_t offset) {
    gl_.EnableVertexAttribArray(index);
    gl_.VertexAttribPointer(index, count, type, normalized, sizeof(Vertex), reinterpret_cast<const void*>(offset));
  };
  attribute(0, 2, GL_FLOAT, GL_FALSE, offsetof(Vertex, x));
  attribute(1, 2, GL_FLOAT, GL_FALSE, offsetof(Vertex, u));
  attribute(2, 4, GL_UNSIGNED_BYTE, GL_TRUE, offsetof(Vertex, color));
  attribute(3, 4, GL_FLOAT, GL_FALSE, offsetof(Vertex, ax));
  attribute(4, 1, GL_FLOAT, GL_FALSE, offsetof(Vertex, half_width));

  const Font& font = Font::instance();
  gl_.ActiveTexture(GL_TEXTURE0);
  gl_.GenTextures(1, &atlas_);
  gl_.BindTexture(GL_TEXTURE_2D, atlas_);
  gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_R8, font.atlas_width(), font.atlas_height(), 0, GL_RED, GL_UNSIGNED_BYTE,
                 font.atlas().data());
  // Nearest: glyphs are placed on whole pixels, so each pixel reads exactly one texel.
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);

  gl_.GenFramebuffers(1, &framebuffer_);
  gl_.GenRenderbuffers(1, &color_buffer_);
  gl_.Enable(GL_BLEND);
  gl_.BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  check("setting up the painter");
}

Painter::~Painter() {
  // Runs with the context current (the worker destroys its painter before its context).
  gl_.DeleteRenderbuffers(1, &color_buffer_);
  gl_.DeleteFramebuffers(1, &framebuffer_);
  gl_.DeleteTextures(1, &atlas_);
  gl_.DeleteBuffers(1, &vertex_buffer_);
  gl_.DeleteVertexArrays(1, &vertex_array_);
  gl_.DeleteProgram(program_);
}

void Painter::check(const char* what) {
  const GLenum error = gl_.GetError();
  if (error != GL_NO_ERROR) {
    throw RenderUnavailable(std::string("OpenGL error ") + std::to_string(error) + " while " + what);
  }
}

void Painter::resize(int width, int height) {
  if (width == width_ && height == height_) return;
  gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  gl_.BindRenderbuffer(GL_RENDERBUFFER, color_buffer_);
  gl_.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_buffer_);
  if (gl_.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    width_ = height_ = 0;
    throw RenderUnavailable("offscreen framebuffer of " + std::to_string(width) + "x" + std::to_string(height) +
                            " is incomplete");
  }
  width_ = width;
  height_ = height;
}

std::vector<std::uint8_t> Painter::paint(const Canvas& canvas) {
  resize(canvas.width(), canvas.height());
  gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  gl_.Viewport(0, 0, width_, height_);
  const Color bg = canvas.background();
  gl_.ClearColor(bg.r / 255.0f, bg.g / 255.0f, bg.b / 255.0f, bg.a / 255.0f);
  gl_.Clear(GL_COLOR_BUFFER_BIT);

  const std::vector<Vertex>& vertices = canvas.vertices();
  gl_.UseProgram(program_);
  gl_.Uniform2f(size_uniform_, static_cast<float>(width_), static_cast<float>(height_));
  gl_.BindVertexArray(vertex_array_);
  gl_.BindBuffer(GL_ARRAY_BUFFER, vertex_buffer_);
  gl_.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(Vertex)), vertices.data(),
                 GL_STREAM_DRAW);
  gl_.ActiveTexture(GL_TEXTURE0);
  gl_.BindTexture(GL_TEXTURE_2D, atlas_);
  gl_.DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(vertices.size()));

  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(width_) * height_ * 3);
  gl_.PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl_.ReadPixels(0, 0, width_, height_, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
  check("drawing");
  return rgb;
}

}  // namespace lienewton::render
