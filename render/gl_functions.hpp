#pragma once
// The OpenGL 3.3 core entry points the painter uses, loaded through the context's proc-address function.
// Loading them (rather than linking libGL) keeps one code path for OSMesa and EGL, whose libraries export
// different symbol sets.
#include <GL/glcorearb.h>

namespace lienewton::render {

class GlContext;

#define LIENEWTON_GL_FUNCTIONS(X)                                                                  \
  X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                                                         \
  X(PFNGLATTACHSHADERPROC, AttachShader)                                                           \
  X(PFNGLBINDBUFFERPROC, BindBuffer)                                                               \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                                                     \
  X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer)                                                   \
  X(PFNGLBINDTEXTUREPROC, BindTexture)                                                             \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                                                     \
  X(PFNGLBLENDFUNCSEPARATEPROC, BlendFuncSeparate)                                                 \
  X(PFNGLBUFFERDATAPROC, BufferData)                                                               \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)                                       \
  X(PFNGLCLEARPROC, Clear)                                                                         \
  X(PFNGLCLEARCOLORPROC, ClearColor)                                                               \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                                                         \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                                                         \
  X(PFNGLCREATESHADERPROC, CreateShader)                                                           \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                                                         \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                                               \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                                                         \
  X(PFNGLDELETERENDERBUFFERSPROC, DeleteRenderbuffers)                                             \
  X(PFNGLDELETESHADERPROC, DeleteShader)                                                           \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures)                                                       \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                                               \
  X(PFNGLDRAWARRAYSPROC, DrawArrays)                                                               \
  X(PFNGLENABLEPROC, Enable)                                                                       \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)                                     \
  X(PFNGLFINISHPROC, Finish)                                                                       \
  X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer)                                     \
  X(PFNGLGENBUFFERSPROC, GenBuffers)                                                               \
  X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                                                     \
  X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers)                                                   \
  X(PFNGLGENTEXTURESPROC, GenTextures)                                                             \
  X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                                                     \
  X(PFNGLGETERRORPROC, GetError)                                                                   \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                                                 \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                                           \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                                                   \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                                                             \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                                               \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                                                             \
  X(PFNGLPIXELSTOREIPROC, PixelStorei)                                                             \
  X(PFNGLREADPIXELSPROC, ReadPixels)                                                               \
  X(PFNGLRENDERBUFFERSTORAGEPROC, RenderbufferStorage)                                             \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                                                           \
  X(PFNGLTEXIMAGE2DPROC, TexImage2D)                                                               \
  X(PFNGLTEXPARAMETERIPROC, TexParameteri)                                                         \
  X(PFNGLUNIFORM1IPROC, Uniform1i)                                                                 \
  X(PFNGLUNIFORM2FPROC, Uniform2f)                                                                 \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                                                               \
  X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)                                             \
  X(PFNGLVIEWPORTPROC, Viewport)

struct GlFunctions {
#define LIENEWTON_GL_MEMBER(type, name) type name = nullptr;
  LIENEWTON_GL_FUNCTIONS(LIENEWTON_GL_MEMBER)
#undef LIENEWTON_GL_MEMBER
};

// Throws RenderUnavailable naming the first entry point the context does not provide.
GlFunctions load_gl_functions(const GlContext& context);

}  // namespace lienewton::render
