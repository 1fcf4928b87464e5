#include "render/canvas.hpp"

#include <cmath>

namespace lienewton::render {

Canvas::Canvas(int width, int height, Color background)
    : width_(width), height_(height), background_(background), font_(Font::instance()) {}

void Canvas::quad(const Point (&corners)[4], const float (&uv)[4], Color color, Point a, Point b, float half_width) {
  // corners in order top-left, top-right, bottom-right, bottom-left; uv = {u0, v0, u1, v1}
  const float us[4] = {uv[0], uv[2], uv[2], uv[0]};
  const float vs[4] = {uv[1], uv[1], uv[3], uv[3]};
  for (int i : {0, 1, 2, 0, 2, 3}) {
    vertices_.push_back({corners[i].x, corners[i].y + dy_, us[i], vs[i], color, a.x, a.y + dy_, b.x, b.y + dy_, half_width});
  }
}

void Canvas::rect(float x0, float y0, float x1, float y1, Color color) {
  Shape s;
  s.a = {x0, y0 + dy_};
  s.b = {x1, y1 + dy_};
  s.color = color;
  shapes_.push_back(std::move(s));
  const float u = font_.solid_u(), v = font_.solid_v();
  quad({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, {u, v, u, v}, color, {}, {}, 0);
}

void Canvas::triangle(Point a, Point b, Point c, Color color) {
  Shape s;
  s.kind = Shape::Kind::triangle;
  s.a = {a.x, a.y + dy_};
  s.b = {b.x, b.y + dy_};
  s.c = {c.x, c.y + dy_};
  s.color = color;
  shapes_.push_back(std::move(s));
  const float u = font_.solid_u(), v = font_.solid_v();
  for (const Point& p : {a, b, c}) vertices_.push_back({p.x, p.y + dy_, u, v, color, 0, 0, 0, 0, 0});
}

void Canvas::line(Point a, Point b, float width, Color color) {
  Shape s;
  s.kind = Shape::Kind::line;
  s.a = {a.x, a.y + dy_};
  s.b = {b.x, b.y + dy_};
  s.width = width;
  s.color = color;
  shapes_.push_back(std::move(s));
  const float half = 0.5f * width;
  const float pad = half + 1.0f;  // room for the antialiased fringe and the round caps
  float dx = b.x - a.x, dy = b.y - a.y;
  const float length = std::hypot(dx, dy);
  if (length > 1e-6f) {
    dx /= length;
    dy /= length;
  } else {
    dx = 1;
    dy = 0;
  }
  const Point along{dx * pad, dy * pad};
  const Point across{-dy * pad, dx * pad};
  const Point corners[4] = {{a.x - along.x + across.x, a.y - along.y + across.y},
                            {b.x + along.x + across.x, b.y + along.y + across.y},
                            {b.x + along.x - across.x, b.y + along.y - across.y},
                            {a.x - along.x - across.x, a.y - along.y - across.y}};
  quad(corners, {0, 0, 0, 0}, color, a, b, half);
}

void Canvas::text(std::string_view text, float x, float y, TextSize size, Color color, Align align) {
  Shape s;
  s.kind = Shape::Kind::text;
  s.a = {x, y + 0.5f * font_.cap_height(size) + dy_};
  s.color = color;
  s.text = std::string(text);
  s.size = size;
  s.align = align;
  shapes_.push_back(std::move(s));
  if (align != Align::left) {
    const float w = font_.width(text, size);
    x -= align == Align::center ? 0.5f * w : w;
  }
  glyphs_.clear();
  font_.layout(text, size, x, y + 0.5f * font_.cap_height(size), glyphs_);
  for (const GlyphQuad& g : glyphs_) {
    quad({{g.x0, g.y0}, {g.x1, g.y0}, {g.x1, g.y1}, {g.x0, g.y1}}, {g.u0, g.v0, g.u1, g.v1}, color, {}, {}, 0);
  }
}

void dashed_line(Canvas& canvas, Point a, Point b, float width, Color color, float dash, float gap) {
  const float length = std::hypot(b.x - a.x, b.y - a.y);
  for (float s = 0; s < length; s += dash + gap) {
    const float e = std::min(s + dash, length);
    canvas.line({a.x + (b.x - a.x) * s / length, a.y + (b.y - a.y) * s / length},
                {a.x + (b.x - a.x) * e / length, a.y + (b.y - a.y) * e / length}, width, color);
  }
}

}  // namespace lienewton::render
