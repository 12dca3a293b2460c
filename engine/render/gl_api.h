#pragma once
/// The OpenGL 3.3 core functions the renderer calls, loaded at run time through the current
/// context's getProcAddress (eglGetProcAddress, OSMesaGetProcAddress, glfwGetProcAddress).
///
/// Why a table instead of linking libOpenGL: OSMesa exports its own gl* symbols, and a binary
/// that links GLVND's libOpenGL as well gets whichever definition the dynamic linker binds first
/// (DESIGN.md, "Notes on the packaged dependencies"). Nothing here references a gl* symbol, so
/// the same binary can drive EGL, OSMesa or a GLFW window, and commands that never draw never
/// touch GL at all. The table is an X-macro: one line per function, used to declare the members
/// and to load them, so the two cannot drift apart.

#include <GL/glcorearb.h>

#include <string>

namespace substep::render {

/// A context's function lookup: returns nullptr for names it does not know.
using GlProcAddress = void (*)();
using GlProcLoader = GlProcAddress (*)(const char* name, void* user);

// X(type, name): `name` is the GL name without its `gl` prefix.
#define SUBSTEP_GL_FUNCTIONS(X)                                                   \
    X(PFNGLGETERRORPROC, GetError)                                                \
    X(PFNGLGETSTRINGPROC, GetString)                                              \
    X(PFNGLGETINTEGERVPROC, GetIntegerv)                                          \
    X(PFNGLENABLEPROC, Enable)                                                    \
    X(PFNGLDISABLEPROC, Disable)                                                  \
    X(PFNGLBLENDFUNCPROC, BlendFunc)                                              \
    X(PFNGLDEPTHFUNCPROC, DepthFunc)                                              \
    X(PFNGLDEPTHMASKPROC, DepthMask)                                              \
    X(PFNGLCULLFACEPROC, CullFace)                                                \
    X(PFNGLPOLYGONOFFSETPROC, PolygonOffset)                                      \
    X(PFNGLVIEWPORTPROC, Viewport)                                                \
    X(PFNGLSCISSORPROC, Scissor)                                                  \
    X(PFNGLCLEARCOLORPROC, ClearColor)                                            \
    X(PFNGLCLEARDEPTHPROC, ClearDepth)                                            \
    X(PFNGLCLEARPROC, Clear)                                                      \
    X(PFNGLFINISHPROC, Finish)                                                    \
    X(PFNGLPIXELSTOREIPROC, PixelStorei)                                          \
    X(PFNGLREADPIXELSPROC, ReadPixels)                                            \
    X(PFNGLREADBUFFERPROC, ReadBuffer)                                            \
    X(PFNGLDRAWBUFFERPROC, DrawBuffer)                                            \
    X(PFNGLDRAWARRAYSPROC, DrawArrays)                                            \
    X(PFNGLDRAWELEMENTSINSTANCEDPROC, DrawElementsInstanced)                      \
    X(PFNGLGENBUFFERSPROC, GenBuffers)                                            \
    X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                                      \
    X(PFNGLBINDBUFFERPROC, BindBuffer)                                            \
    X(PFNGLBUFFERDATAPROC, BufferData)                                            \
    X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                                  \
    X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                            \
    X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                                  \
    X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)                  \
    X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)                          \
    X(PFNGLVERTEXATTRIBDIVISORPROC, VertexAttribDivisor)                          \
    X(PFNGLCREATESHADERPROC, CreateShader)                                        \
    X(PFNGLDELETESHADERPROC, DeleteShader)                                        \
    X(PFNGLSHADERSOURCEPROC, ShaderSource)                                        \
    X(PFNGLCOMPILESHADERPROC, CompileShader)                                      \
    X(PFNGLGETSHADERIVPROC, GetShaderiv)                                          \
    X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                                \
    X(PFNGLCREATEPROGRAMPROC, CreateProgram)                                      \
    X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                                      \
    X(PFNGLATTACHSHADERPROC, AttachShader)                                        \
    X(PFNGLLINKPROGRAMPROC, LinkProgram)                                          \
    X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                        \
    X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                              \
    X(PFNGLUSEPROGRAMPROC, UseProgram)                                            \
    X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                            \
    X(PFNGLUNIFORM1IPROC, Uniform1i)                                              \
    X(PFNGLUNIFORM1FPROC, Uniform1f)                                              \
    X(PFNGLUNIFORM3FVPROC, Uniform3fv)                                            \
    X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)                                \
    X(PFNGLGENTEXTURESPROC, GenTextures)                                          \
    X(PFNGLDELETETEXTURESPROC, DeleteTextures)                                    \
    X(PFNGLBINDTEXTUREPROC, BindTexture)                                          \
    X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                                      \
    X(PFNGLTEXIMAGE2DPROC, TexImage2D)                                            \
    X(PFNGLTEXPARAMETERIPROC, TexParameteri)                                      \
    X(PFNGLTEXPARAMETERFVPROC, TexParameterfv)                                    \
    X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                                  \
    X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                            \
    X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                                  \
    X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D)                        \
    X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer)                  \
    X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)                    \
    X(PFNGLBLITFRAMEBUFFERPROC, BlitFramebuffer)                                  \
    X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers)                                \
    X(PFNGLDELETERENDERBUFFERSPROC, DeleteRenderbuffers)                          \
    X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer)                                \
    X(PFNGLRENDERBUFFERSTORAGEMULTISAMPLEPROC, RenderbufferStorageMultisample)

/// The loaded functions of one context. Call sites read `gl.Clear(GL_COLOR_BUFFER_BIT)`.
struct GlApi {
#define SUBSTEP_GL_MEMBER(type, name) type name = nullptr;
    SUBSTEP_GL_FUNCTIONS(SUBSTEP_GL_MEMBER)
#undef SUBSTEP_GL_MEMBER
};

/// Loads every function of the table through `loader`. Throws std::runtime_error naming the
/// first missing function (the context is not OpenGL 3.3 core capable).
GlApi loadGlApi(GlProcLoader loader, void* user);

/// "GL_INVALID_OPERATION" and friends, for error messages.
std::string glErrorName(GLenum error);

}  // namespace substep::render
