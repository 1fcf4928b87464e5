#pragma once
#include "render/renderer.hpp"

namespace lienewton::render::testing {

// One renderer for the scene tests: a context per test would spend most of the time in shader JIT.
Renderer& shared_renderer();

}  // namespace lienewton::render::testing
