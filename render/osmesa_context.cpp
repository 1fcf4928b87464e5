// GlContext on OSMesa (gallium llvmpipe). Rendering goes to the painter's FBOs; the 1x1 OSMesa buffer only
// exists because OSMesaMakeCurrent requires one.
#include <GL/osmesa.h>

#include <array>

#include "render/gl_context.hpp"
#include "render/render_unavailable.hpp"

namespace lienewton::render {

struct GlContext::Impl {
  OSMesaContext context = nullptr;
  std::array<unsigned char, 4> buffer{};
};

GlContext::GlContext() : impl_(std::make_unique<Impl>()) {
  const int attributes[] = {OSMESA_FORMAT,       OSMESA_RGBA, OSMESA_DEPTH_BITS, 0,
                            OSMESA_STENCIL_BITS, 0,           OSMESA_ACCUM_BITS, 0,
                            OSMESA_PROFILE,      OSMESA_CORE_PROFILE,
                            OSMESA_CONTEXT_MAJOR_VERSION, 3,
                            OSMESA_CONTEXT_MINOR_VERSION, 3,
                            0};
  impl_->context = OSMesaCreateContextAttribs(attributes, nullptr);
  if (impl_->context == nullptr) throw RenderUnavailable("OSMesa: cannot create an OpenGL 3.3 core context");
}

GlContext::~GlContext() {
  if (impl_->context != nullptr) OSMesaDestroyContext(impl_->context);
}

void GlContext::make_current() {
  if (!OSMesaMakeCurrent(impl_->context, impl_->buffer.data(), GL_UNSIGNED_BYTE, 1, 1)) {
    throw RenderUnavailable("OSMesa: cannot make the context current");
  }
}

void GlContext::release() { OSMesaMakeCurrent(nullptr, nullptr, GL_UNSIGNED_BYTE, 0, 0); }

GlProc GlContext::proc_address(const char* name) const {
  return reinterpret_cast<GlProc>(OSMesaGetProcAddress(name));
}

}  // namespace lienewton::render
