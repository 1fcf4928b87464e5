// GlContext on EGL's Mesa surfaceless platform: no window system and no surface; the painter renders
// into FBOs. Works where OSMesa is gone (Mesa >= 25.1).
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdio>
#include <mutex>
#include <string>

#include "render/gl_context.hpp"
#include "render/render_unavailable.hpp"

namespace lienewton::render {
namespace {

std::string egl_error(const char* what) {
  char code[16];
  std::snprintf(code, sizeof code, "0x%x", static_cast<unsigned>(eglGetError()));
  return std::string("EGL: ") + what + " (error " + code + ")";
}

// One display per process, initialised once and kept: eglTerminate would destroy every worker's context.
EGLDisplay surfaceless_display() {
  static EGLDisplay display = EGL_NO_DISPLAY;
  static std::string failure;
  static std::once_flag once;
  std::call_once(once, [] {
    auto get_platform_display =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (get_platform_display == nullptr) {
      failure = "EGL: eglGetPlatformDisplayEXT is missing";
      return;
    }
    EGLDisplay candidate = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (candidate == EGL_NO_DISPLAY || !eglInitialize(candidate, nullptr, nullptr)) {
      failure = egl_error("cannot initialise the surfaceless display");
      return;
    }
    display = candidate;
  });
  if (display == EGL_NO_DISPLAY) throw RenderUnavailable(failure);
  return display;
}

}  // namespace

struct GlContext::Impl {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
};

GlContext::GlContext() : impl_(std::make_unique<Impl>()) {
  impl_->display = surfaceless_display();
  if (!eglBindAPI(EGL_OPENGL_API)) throw RenderUnavailable(egl_error("no desktop OpenGL API"));
  const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  // EGL_KHR_no_config_context: the context never draws to an EGL surface, so it needs no config.
  impl_->context = eglCreateContext(impl_->display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
  if (impl_->context == EGL_NO_CONTEXT) throw RenderUnavailable(egl_error("cannot create an OpenGL 3.3 core context"));
}

GlContext::~GlContext() {
  if (impl_->context != EGL_NO_CONTEXT) eglDestroyContext(impl_->display, impl_->context);
}

void GlContext::make_current() {
  if (!eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, impl_->context)) {
    throw RenderUnavailable(egl_error("cannot make the context current"));
  }
}

void GlContext::release() { eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT); }

GlProc GlContext::proc_address(const char* name) const { return eglGetProcAddress(name); }

}  // namespace lienewton::render
