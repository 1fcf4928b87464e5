#include "render/caption.hpp"

#include <cmath>

namespace lienewton::render {
namespace {

constexpr int kMargin = 10;
constexpr int kGap = 4;  // between lines
constexpr const char* kSeparator = " \u00b7 ";

float width_of(const std::string& text, TextSize size) { return Font::instance().width(text, size); }
int height_of(TextSize size) { return static_cast<int>(std::ceil(Font::instance().pixel_height(size))); }

}  // namespace

std::vector<std::string> caption_lines(const Caption& caption, int width) {
  std::vector<std::string> lines;
  if (!caption.title.empty()) lines.push_back(caption.title);
  const float room = static_cast<float>(width - 2 * kMargin);
  std::string line;
  std::size_t from = 0;
  while (from < caption.subtitle.size()) {
    std::size_t to = caption.subtitle.find(kSeparator, from);
    if (to == std::string::npos) to = caption.subtitle.size();
    const std::string fact = caption.subtitle.substr(from, to - from);
    const std::string longer = line.empty() ? fact : line + kSeparator + fact;
    if (!line.empty() && width_of(longer, TextSize::small) > room) {
      lines.push_back(line);
      line = fact;
    } else {
      line = longer;
    }
    from = to == caption.subtitle.size() ? to : to + std::string(kSeparator).size();
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

int caption_height(const Caption& caption, int width) {
  const std::vector<std::string> lines = caption_lines(caption, width);
  if (lines.empty()) return 0;
  const int title = caption.title.empty() ? 0 : height_of(TextSize::large) + kGap;
  const int rest = static_cast<int>(lines.size()) - (caption.title.empty() ? 0 : 1);
  return kMargin + title + rest * (height_of(TextSize::small) + kGap) + kMargin / 2;
}

void draw_caption(Canvas& canvas, const Caption& caption) {
  const std::vector<std::string> lines = caption_lines(caption, canvas.width());
  float y = kMargin;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const bool title = i == 0 && !caption.title.empty();
    const TextSize size = title ? TextSize::large : TextSize::small;
    const float h = Font::instance().pixel_height(size);
    canvas.text(lines[i], kMargin, y + 0.5f * h, size, kTextColor);
    y += h + kGap;
  }
  canvas.shift_down(static_cast<float>(caption_height(caption, canvas.width())));
}

}  // namespace lienewton::render
