#pragma once
// The vector copy of a picture: every shape a scene drew on its Canvas as SVG elements (rects, round-capped lines,
// triangles, text in the label font), plus raster parts drawn straight into the pixels (a basin map's panels) as
// embedded PNG images. For papers: the text stays text, the lines stay lines at any zoom.
#include <cstdint>
#include <string>
#include <vector>

#include "render/canvas.hpp"

namespace lienewton::render {

// A raster part of the picture: a PNG shown at (x, y), width x height pixels, without smoothing.
struct SvgImage {
  float x = 0, y = 0, width = 0, height = 0;
  std::vector<std::uint8_t> png;
};

// An SVG document of canvas.width() x canvas.height() pixels on the canvas' background.
std::string to_svg(const Canvas& canvas, const std::vector<SvgImage>& images = {});

}  // namespace lienewton::render
