#pragma once
// The drift of a problem's invariants along one integration: |I(y_k) - I(y_0)| / |I(y_0)| on a log axis against
// the step k, one line per invariant the run reports (rigid body: energy; heavy top: energy and vertical momentum), each
// legend entry with the run's drift (the largest value).
#include <string>

#include "core/integrate.hpp"
#include "render/figure.hpp"

namespace lienewton::render {

// Steps whose value equals I(y_0) exactly (no point on a log axis) or is not finite are left out. Throws
// std::invalid_argument when no point is left; width and height as Renderer's.
Figure invariants_scene(const IntegrateResult& result, const std::string& title, int width, int height);

}  // namespace lienewton::render
