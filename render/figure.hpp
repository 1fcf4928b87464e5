#pragma once
// A picture made of line charts, each in its own frame (the residual figure sets two side by side).
#include <vector>

#include "render/line_chart_scene.hpp"

namespace lienewton::render {

struct ChartPanel {
  LineChart chart;
  Box frame;
};

struct Figure {
  int width = 0, height = 0;
  std::vector<ChartPanel> panels;
};

// Lays out and draws every panel. Throws std::invalid_argument as layout_line_chart does.
void draw_figure(Canvas& canvas, const Figure& figure);

}  // namespace lienewton::render
