#pragma once
// The work-precision diagram (as in Hairer-Wanner or DiffEqDevTools): solver CPU time against global error,
// one line per (integrator, method, differential) joining its step sizes from the largest h to the smallest,
// a marker per h, and a legend with each series' fitted order p (error ~ h^p).
#include <string>

#include "core/work_precision.hpp"
#include "render/figure.hpp"

namespace lienewton::render {

// Series are styled by their position in result (series_style). Points that did not converge, or whose
// error or time is not positive, are left out and counted in the legend. Throws std::invalid_argument when
// no point is left; width and height as Renderer's.
Figure work_precision_scene(const WorkPrecisionResult& result, const std::string& title, int width, int height);

}  // namespace lienewton::render
