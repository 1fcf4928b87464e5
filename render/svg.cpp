#include "render/svg.hpp"

#include <cstdio>

#include "render/font.hpp"

namespace lienewton::render {
namespace {

std::string number(float x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", x);
  std::string s = text;
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  return s;
}

std::string rgb(Color c) {
  return "rgb(" + std::to_string(c.r) + "," + std::to_string(c.g) + "," + std::to_string(c.b) + ")";
}

// fill="..." or stroke="...", with its opacity where the colour is translucent.
std::string paint(const char* what, Color c) {
  std::string out = std::string(" ") + what + "=\"" + rgb(c) + "\"";
  if (c.a != 255) out += std::string(" ") + what + "-opacity=\"" + number(c.a / 255.0f) + "\"";
  return out;
}

std::string escaped(const std::string& text) {
  std::string out;
  for (char ch : text) {
    switch (ch) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += ch;
    }
  }
  return out;
}

std::string base64(const std::vector<std::uint8_t>& bytes) {
  static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const unsigned v = bytes[i] << 16 | (i + 1 < bytes.size() ? bytes[i + 1] << 8 : 0) |
                       (i + 2 < bytes.size() ? bytes[i + 2] : 0);
    out += kDigits[v >> 18 & 63];
    out += kDigits[v >> 12 & 63];
    out += i + 1 < bytes.size() ? kDigits[v >> 6 & 63] : '=';
    out += i + 2 < bytes.size() ? kDigits[v & 63] : '=';
  }
  return out;
}

}  // namespace

std::string to_svg(const Canvas& canvas, const std::vector<SvgImage>& images) {
  const std::string w = std::to_string(canvas.width()), h = std::to_string(canvas.height());
  std::string out = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + w + "\" height=\"" + h + "\" viewBox=\"0 0 " +
                    w + " " + h + "\" font-family=\"DejaVu Sans, Verdana, sans-serif\">\n";
  out += "<rect width=\"" + w + "\" height=\"" + h + "\"" + paint("fill", canvas.background()) + "/>\n";
  for (const SvgImage& image : images) {
    out += "<image x=\"" + number(image.x) + "\" y=\"" + number(image.y) + "\" width=\"" + number(image.width) +
           "\" height=\"" + number(image.height) + "\" style=\"image-rendering:pixelated\" href=\"data:image/png;base64," +
           base64(image.png) + "\"/>\n";
  }
  const Font& font = Font::instance();
  for (const Shape& s : canvas.shapes()) {
    switch (s.kind) {
      case Shape::Kind::rect:
        out += "<rect x=\"" + number(s.a.x) + "\" y=\"" + number(s.a.y) + "\" width=\"" + number(s.b.x - s.a.x) +
               "\" height=\"" + number(s.b.y - s.a.y) + "\"" + paint("fill", s.color) + "/>\n";
        break;
      case Shape::Kind::line:
        out += "<line x1=\"" + number(s.a.x) + "\" y1=\"" + number(s.a.y) + "\" x2=\"" + number(s.b.x) + "\" y2=\"" +
               number(s.b.y) + "\"" + paint("stroke", s.color) + " stroke-width=\"" + number(s.width) +
               "\" stroke-linecap=\"round\"/>\n";
        break;
      case Shape::Kind::triangle:
        out += "<polygon points=\"" + number(s.a.x) + "," + number(s.a.y) + " " + number(s.b.x) + "," + number(s.b.y) +
               " " + number(s.c.x) + "," + number(s.c.y) + "\"" + paint("fill", s.color) + "/>\n";
        break;
      case Shape::Kind::text: {
        const char* anchor = s.align == Align::left ? "start" : s.align == Align::center ? "middle" : "end";
        out += "<text x=\"" + number(s.a.x) + "\" y=\"" + number(s.a.y) + "\" font-size=\"" +
               number(font.em_size(s.size)) + "\" text-anchor=\"" + anchor + "\"" + paint("fill", s.color) + ">" +
               escaped(s.text) + "</text>\n";
        break;
      }
    }
  }
  return out + "</svg>\n";
}

}  // namespace lienewton::render
