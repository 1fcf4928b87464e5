#pragma once
// A picture's title and subtitle, in a band above its scene: what the picture shows (the problem or the user's
// g, the group, N, h, the method, the differential, tol), so that a PNG read away from the page still says it.
#include <string>
#include <vector>

#include "render/canvas.hpp"

namespace lienewton::render {

struct Caption {
  std::string title;
  // Facts joined by " · "; wrapped between facts where the picture is too narrow for one line.
  std::string subtitle;
};

// The caption's lines for a picture `width` pixels wide: the title's (wrapped between words where the picture is
// too narrow: a phone's), then the subtitle's (wrapped between facts).
struct CaptionLines {
  std::vector<std::string> title;
  std::vector<std::string> subtitle;
};
CaptionLines caption_lines(const Caption& caption, int width);
// The band's height in pixels (0 for an empty caption).
int caption_height(const Caption& caption, int width);
// Draws the caption at the top of the canvas and shifts what is drawn after it below the band.
void draw_caption(Canvas& canvas, const Caption& caption);

}  // namespace lienewton::render
