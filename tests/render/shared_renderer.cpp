#include "shared_renderer.hpp"

namespace lienewton::render::testing {

// Never destroyed: its contexts must not be torn down among the exit handlers, after OSMesa's own (gl_context.hpp).
Renderer& shared_renderer() {
  static Renderer& renderer = *new Renderer(1);
  return renderer;
}

}  // namespace lienewton::render::testing
