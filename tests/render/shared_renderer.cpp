#include "shared_renderer.hpp"

namespace lienewton::render::testing {

Renderer& shared_renderer() {
  static Renderer renderer(1);
  return renderer;
}

}  // namespace lienewton::render::testing
