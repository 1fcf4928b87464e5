#include "render/gl_functions.hpp"

#include <string>

#include "render/gl_context.hpp"
#include "render/render_unavailable.hpp"

namespace lienewton::render {

GlFunctions load_gl_functions(const GlContext& context) {
  GlFunctions gl;
#define LIENEWTON_GL_LOAD(type, name)                                                     \
  gl.name = reinterpret_cast<type>(context.proc_address("gl" #name));                     \
  if (gl.name == nullptr) throw RenderUnavailable("OpenGL entry point gl" #name " is missing");
  LIENEWTON_GL_FUNCTIONS(LIENEWTON_GL_LOAD)
#undef LIENEWTON_GL_LOAD
  return gl;
}

}  // namespace lienewton::render
