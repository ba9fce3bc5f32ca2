// The GL entry points the renderer uses, resolved at run time through the context's own
// getProcAddress: the window gets them from GLFW (libGL), the headless path from OSMesa, which
// exports GL itself. Because no GL symbol is linked directly, one program can hold both paths.
// (libepoxy was the first choice, but it resolves only through GLX or EGL: with an OSMesa context
// current its glGetString returns null.)
#pragma once

#include <GL/glcorearb.h>

#include <functional>

namespace hirsute {

using GlProc = void (*)();
using GetProcAddress = std::function<GlProc(const char* name)>;

// X(pointer type, name without the gl prefix) for every function in the table.
#define HIRSUTE_GL_FUNCTIONS(X)                                              \
  X(PFNGLGETSTRINGPROC, GetString)                                           \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                                       \
  X(PFNGLGETERRORPROC, GetError)                                             \
  X(PFNGLENABLEPROC, Enable)                                                 \
  X(PFNGLDISABLEPROC, Disable)                                               \
  X(PFNGLVIEWPORTPROC, Viewport)                                             \
  X(PFNGLCLEARCOLORPROC, ClearColor)                                         \
  X(PFNGLCLEARDEPTHPROC, ClearDepth)                                         \
  X(PFNGLCLEARPROC, Clear)                                                   \
  X(PFNGLDEPTHFUNCPROC, DepthFunc)                                           \
  X(PFNGLDEPTHMASKPROC, DepthMask)                                           \
  X(PFNGLBLENDFUNCPROC, BlendFunc)                                           \
  X(PFNGLPOLYGONMODEPROC, PolygonMode)                                       \
  X(PFNGLFINISHPROC, Finish)                                                 \
  X(PFNGLPIXELSTOREIPROC, PixelStorei)                                       \
  X(PFNGLREADPIXELSPROC, ReadPixels)                                         \
  X(PFNGLCREATESHADERPROC, CreateShader)                                     \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                                     \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                                   \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                                       \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                             \
  X(PFNGLDELETESHADERPROC, DeleteShader)                                     \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                                   \
  X(PFNGLATTACHSHADERPROC, AttachShader)                                     \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                                       \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                     \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                           \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                                   \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                                         \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                         \
  X(PFNGLUNIFORM1IPROC, Uniform1i)                                           \
  X(PFNGLUNIFORM1FPROC, Uniform1f)                                           \
  X(PFNGLUNIFORM2FPROC, Uniform2f)                                           \
  X(PFNGLUNIFORM3FVPROC, Uniform3fv)                                         \
  X(PFNGLUNIFORM4FVPROC, Uniform4fv)                                         \
  X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)                             \
  X(PFNGLGENBUFFERSPROC, GenBuffers)                                         \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                                   \
  X(PFNGLBINDBUFFERPROC, BindBuffer)                                         \
  X(PFNGLBUFFERDATAPROC, BufferData)                                         \
  X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                               \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                         \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                               \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)               \
  X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)                       \
  X(PFNGLVERTEXATTRIBIPOINTERPROC, VertexAttribIPointer)                     \
  X(PFNGLDRAWARRAYSPROC, DrawArrays)                                         \
  X(PFNGLDRAWELEMENTSPROC, DrawElements)                                     \
  X(PFNGLDRAWARRAYSINSTANCEDPROC, DrawArraysInstanced)                       \
  X(PFNGLDRAWELEMENTSINSTANCEDPROC, DrawElementsInstanced)                   \
  X(PFNGLVERTEXATTRIBDIVISORPROC, VertexAttribDivisor)                       \
  X(PFNGLGENTEXTURESPROC, GenTextures)                                       \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures)                                 \
  X(PFNGLBINDTEXTUREPROC, BindTexture)                                       \
  X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                                   \
  X(PFNGLTEXIMAGE2DPROC, TexImage2D)                                         \
  X(PFNGLTEXPARAMETERIPROC, TexParameteri)                                   \
  X(PFNGLGENERATEMIPMAPPROC, GenerateMipmap)                                 \
  X(PFNGLTEXBUFFERPROC, TexBuffer)                                           \
  X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                               \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                         \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                               \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)                 \
  X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer)               \
  X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers)                             \
  X(PFNGLDELETERENDERBUFFERSPROC, DeleteRenderbuffers)                       \
  X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer)                             \
  X(PFNGLRENDERBUFFERSTORAGEPROC, RenderbufferStorage)                       \
  X(PFNGLRENDERBUFFERSTORAGEMULTISAMPLEPROC, RenderbufferStorageMultisample) \
  X(PFNGLBLITFRAMEBUFFERPROC, BlitFramebuffer)                               \
  X(PFNGLREADBUFFERPROC, ReadBuffer)

// The table, filled for the context that is current when it is built. Calls read `gl.Clear(…)`.
struct GlFunctions {
#define HIRSUTE_GL_DECLARE(type, name) type name = nullptr;
  HIRSUTE_GL_FUNCTIONS(HIRSUTE_GL_DECLARE)
#undef HIRSUTE_GL_DECLARE

  // Resolves every entry point; throws std::runtime_error naming the first that is missing.
  explicit GlFunctions(const GetProcAddress& resolve);
};

}  // namespace hirsute
