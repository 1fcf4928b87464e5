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

namespace {

// text's pieces between separators, joined greedily into lines no wider than room (a piece wider than room keeps
// a line of its own).
std::vector<std::string> wrapped(const std::string& text, const std::string& separator, TextSize size, float room) {
  std::vector<std::string> lines;
  std::string line;
  std::size_t from = 0;
  while (from < text.size()) {
    std::size_t to = text.find(separator, from);
    if (to == std::string::npos) to = text.size();
    const std::string piece = text.substr(from, to - from);
    const std::string longer = line.empty() ? piece : line + separator + piece;
    if (!line.empty() && width_of(longer, size) > room) {
      lines.push_back(line);
      line = piece;
    } else {
      line = longer;
    }
    from = to == text.size() ? to : to + separator.size();
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

}  // namespace

CaptionLines caption_lines(const Caption& caption, int width) {
  const float room = static_cast<float>(width - 2 * kMargin);
  return {wrapped(caption.title, " ", TextSize::large, room), wrapped(caption.subtitle, kSeparator, TextSize::small, room)};
}

int caption_height(const Caption& caption, int width) {
  const CaptionLines lines = caption_lines(caption, width);
  if (lines.title.empty() && lines.subtitle.empty()) return 0;
  return kMargin + static_cast<int>(lines.title.size()) * (height_of(TextSize::large) + kGap) +
         static_cast<int>(lines.subtitle.size()) * (height_of(TextSize::small) + kGap) + kMargin / 2;
}

void draw_caption(Canvas& canvas, const Caption& caption) {
  const CaptionLines lines = caption_lines(caption, canvas.width());
  float y = kMargin;
  for (const auto& [texts, size] : {std::pair{&lines.title, TextSize::large}, std::pair{&lines.subtitle, TextSize::small}}) {
    const float h = Font::instance().pixel_height(size);
    for (const std::string& line : *texts) {
      canvas.text(line, kMargin, y + 0.5f * h, size, kTextColor);
      y += h + kGap;
    }
  }
  canvas.shift_down(static_cast<float>(caption_height(caption, canvas.width())));
}

}  // namespace lienewton::render
