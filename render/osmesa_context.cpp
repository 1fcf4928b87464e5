// GlContext on OSMesa (gallium llvmpipe). Rendering goes to the painter's FBOs; the 1x1 OSMesa buffer only
// exists because OSMesaMakeCurrent requires one.
//
// libOSMesa is opened on the first context, not linked: it brings LLVM, whose relocation at load cost every process
// most of its start (a CLI command that draws nothing, each server and Python start), and most processes never draw.
// Its file name (LIENEWTON_OSMESA_LIBRARY, the SONAME the build found) is the one the build's headers describe.
#include <GL/osmesa.h>
#include <dlfcn.h>

#include <array>
#include <string>

#include "render/gl_context.hpp"
#include "render/render_unavailable.hpp"

namespace lienewton::render {
namespace {

struct OsMesa {
  decltype(&OSMesaCreateContextAttribs) create_context = nullptr;
  decltype(&OSMesaDestroyContext) destroy_context = nullptr;
  decltype(&OSMesaMakeCurrent) make_current = nullptr;
  decltype(&OSMesaGetProcAddress) proc_address = nullptr;
  std::string error;  // why it could not be opened
};

template <class F>
void resolve(void* library, const char* name, F& f, std::string& error) {
  f = reinterpret_cast<F>(dlsym(library, name));
  if (f == nullptr && error.empty()) error = std::string("OSMesa: ") + LIENEWTON_OSMESA_LIBRARY + " has no " + name;
}

// Opened once per process (thread-safe static initialisation) and never closed: contexts live until exit.
const OsMesa& osmesa() {
  static const OsMesa api = [] {
    OsMesa a;
    void* library = dlopen(LIENEWTON_OSMESA_LIBRARY, RTLD_NOW | RTLD_LOCAL);
    if (library == nullptr) {
      const char* why = dlerror();
      a.error = std::string("OSMesa: cannot open ") + LIENEWTON_OSMESA_LIBRARY + (why ? std::string(": ") + why : "");
      return a;
    }
    resolve(library, "OSMesaCreateContextAttribs", a.create_context, a.error);
    resolve(library, "OSMesaDestroyContext", a.destroy_context, a.error);
    resolve(library, "OSMesaMakeCurrent", a.make_current, a.error);
    resolve(library, "OSMesaGetProcAddress", a.proc_address, a.error);
    return a;
  }();
  if (!api.error.empty()) throw RenderUnavailable(api.error);
  return api;
}

}  // namespace

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
  impl_->context = osmesa().create_context(attributes, nullptr);
  if (impl_->context == nullptr) throw RenderUnavailable("OSMesa: cannot create an OpenGL 3.3 core context");
}

GlContext::~GlContext() {
  if (impl_->context != nullptr) osmesa().destroy_context(impl_->context);
}

void GlContext::make_current() {
  if (!osmesa().make_current(impl_->context, impl_->buffer.data(), GL_UNSIGNED_BYTE, 1, 1)) {
    throw RenderUnavailable("OSMesa: cannot make the context current");
  }
}

void GlContext::release() { osmesa().make_current(nullptr, nullptr, GL_UNSIGNED_BYTE, 0, 0); }

GlProc GlContext::proc_address(const char* name) const {
  return reinterpret_cast<GlProc>(osmesa().proc_address(name));
}

}  // namespace lienewton::render
