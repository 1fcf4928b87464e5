#pragma once
// An offscreen OpenGL 3.3 core context. The backend (OSMesa or EGL surfaceless) is chosen at build time by
// LIENEWTON_GL_BACKEND; both render into framebuffer objects that the painter owns, so the context itself
// needs no drawable. A context is long-lived and current in at most one thread at a time. Destroy every context
// before exit() begins (a renderer owned by main's scope, or one never destroyed): OSMesa is opened with the first
// context, so its own exit handlers run before those of anything constructed earlier, a function-static renderer's.
#include <memory>

namespace lienewton::render {

using GlProc = void (*)();

class GlContext {
 public:
  // Throws RenderUnavailable when no context can be created.
  GlContext();
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  void make_current();  // on the calling thread; throws RenderUnavailable on failure
  void release();       // detach from the calling thread so that another thread may take it
  GlProc proc_address(const char* name) const;  // nullptr when the entry point is unknown

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// llvmpipe reads LP_NUM_THREADS once, when the first context of the process is created. This sets it
// (unless the environment already does) before that; later calls have no effect.
void set_rasterizer_threads(int threads);

}  // namespace lienewton::render
