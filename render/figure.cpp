#include "render/figure.hpp"

namespace lienewton::render {

void draw_figure(Canvas& canvas, const Figure& figure) {
  for (const ChartPanel& panel : figure.panels) draw_line_chart(canvas, panel.chart, layout_line_chart(panel.chart, panel.frame));
}

}  // namespace lienewton::render
