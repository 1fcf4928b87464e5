#pragma once
// A picture as a flat list of triangles in top-down pixel coordinates: filled rectangles, antialiased
// round-capped lines and text. Scenes fill a Canvas on the CPU; the painter draws it in one GL call.
#include <string>
#include <string_view>
#include <vector>

#include "render/color.hpp"
#include "render/font.hpp"

namespace lienewton::render {

struct Point {
  float x = 0, y = 0;
};

// The vertex layout the painter's shader reads. A vertex with half_width > 0 belongs to a line and gets
// its coverage from its distance to the segment (a, b); otherwise from the atlas texel at (u, v).
struct Vertex {
  float x, y;
  float u, v;
  Color color;
  float ax, ay, bx, by;
  float half_width;
};

enum class Align { left, center, right };

// What was drawn, in drawing order and picture coordinates: the vector copy of the picture (svg.hpp).
struct Shape {
  enum class Kind { rect, line, triangle, text };
  Kind kind = Kind::rect;
  Point a{}, b{}, c{};  // rect: top-left a, bottom-right b; line: ends a, b; triangle: a, b, c; text: anchor a, on the baseline
  float width = 0;      // a line's width
  Color color{};
  std::string text{};
  TextSize size = TextSize::small;
  Align align = Align::left;
};

class Canvas {
 public:
  Canvas(int width, int height, Color background);

  int width() const { return width_; }
  int height() const { return height_; }
  Color background() const { return background_; }
  const std::vector<Vertex>& vertices() const { return vertices_; }
  const std::vector<Shape>& shapes() const { return shapes_; }

  // Moves everything drawn after this down by dy pixels (a caption band above a scene drawn at y = 0).
  void shift_down(float dy) { dy_ += dy; }
  // The height below the band: what a scene that lays itself out from the canvas' size has to fill.
  float scene_height() const { return static_cast<float>(height_) - dy_; }

  void rect(float x0, float y0, float x1, float y1, Color color);
  void line(Point a, Point b, float width, Color color);
  void triangle(Point a, Point b, Point c, Color color);  // filled, not antialiased
  // y is the vertical middle of capital letters; x is the left edge, middle or right edge per align.
  void text(std::string_view text, float x, float y, TextSize size, Color color, Align align = Align::left);

 private:
  void quad(const Point (&corners)[4], const float (&uv)[4], Color color, Point a, Point b, float half_width);

  int width_;
  int height_;
  Color background_;
  float dy_ = 0;
  const Font& font_;
  std::vector<Vertex> vertices_;
  std::vector<Shape> shapes_;
  std::vector<GlyphQuad> glyphs_;  // scratch
};

// A dashed line from a to b: dashes of `dash` pixels with `gap` between them.
void dashed_line(Canvas& canvas, Point a, Point b, float width, Color color, float dash = 7, float gap = 5);

}  // namespace lienewton::render
