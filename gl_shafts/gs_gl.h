/* The OpenGL 4.5 core entry points gl_shafts uses, loaded once through
 * OSMesaGetProcAddress (libOSMesa does not export most post-1.1 functions),
 * and the check that turns GL errors into sh_error reports.
 *
 * Every file that calls GL includes this header instead of <GL/gl.h>: the
 * names below (glClear, glCreateTextures, ...) are macros for the loaded
 * pointers, so code reads like ordinary GL. A GL function missing from the
 * table fails to compile (it has no prototype), so the table and the code
 * cannot drift apart silently. */
#ifndef GS_GL_H
#define GS_GL_H

#include <GL/glcorearb.h>

#include "gs_gl_load.h"
#include "sh_error.h"

#define GS__GL_FUNCS(X)                                                      \
  X(PFNGLGETERRORPROC, GetError)                                             \
  X(PFNGLGETSTRINGPROC, GetString)                                           \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                                       \
  X(PFNGLFINISHPROC, Finish)                                                 \
  X(PFNGLENABLEPROC, Enable)                                                 \
  X(PFNGLDISABLEPROC, Disable)                                               \
  X(PFNGLBLENDFUNCPROC, BlendFunc)                                           \
  X(PFNGLBLENDEQUATIONPROC, BlendEquation)                                   \
  X(PFNGLDEPTHFUNCPROC, DepthFunc)                                           \
  X(PFNGLDEPTHMASKPROC, DepthMask)                                           \
  X(PFNGLVIEWPORTPROC, Viewport)                                             \
  X(PFNGLPOLYGONOFFSETPROC, PolygonOffset)                                   \
  X(PFNGLCULLFACEPROC, CullFace)                                             \
  X(PFNGLCLIPCONTROLPROC, ClipControl)                                       \
  X(PFNGLREADPIXELSPROC, ReadPixels)                                         \
  X(PFNGLPIXELSTOREIPROC, PixelStorei)                                       \
  X(PFNGLDRAWARRAYSPROC, DrawArrays)                                         \
  X(PFNGLMULTIDRAWARRAYSPROC, MultiDrawArrays)                               \
  X(PFNGLCREATETEXTURESPROC, CreateTextures)                                 \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures)                                 \
  X(PFNGLTEXTURESTORAGE2DPROC, TextureStorage2D)                             \
  X(PFNGLTEXTURESTORAGE3DPROC, TextureStorage3D)                             \
  X(PFNGLTEXTURESUBIMAGE2DPROC, TextureSubImage2D)                           \
  X(PFNGLTEXTURESUBIMAGE3DPROC, TextureSubImage3D)                           \
  X(PFNGLTEXTUREPARAMETERIPROC, TextureParameteri)                           \
  X(PFNGLTEXTUREPARAMETERFVPROC, TextureParameterfv)                         \
  X(PFNGLBINDTEXTUREUNITPROC, BindTextureUnit)                               \
  X(PFNGLCREATEFRAMEBUFFERSPROC, CreateFramebuffers)                         \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                         \
  X(PFNGLNAMEDFRAMEBUFFERTEXTUREPROC, NamedFramebufferTexture)               \
  X(PFNGLNAMEDFRAMEBUFFERTEXTURELAYERPROC, NamedFramebufferTextureLayer)     \
  X(PFNGLNAMEDFRAMEBUFFERDRAWBUFFERSPROC, NamedFramebufferDrawBuffers)       \
  X(PFNGLNAMEDFRAMEBUFFERDRAWBUFFERPROC, NamedFramebufferDrawBuffer)         \
  X(PFNGLNAMEDFRAMEBUFFERREADBUFFERPROC, NamedFramebufferReadBuffer)         \
  X(PFNGLCHECKNAMEDFRAMEBUFFERSTATUSPROC, CheckNamedFramebufferStatus)       \
  X(PFNGLCLEARNAMEDFRAMEBUFFERFVPROC, ClearNamedFramebufferfv)               \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                               \
  X(PFNGLCREATEBUFFERSPROC, CreateBuffers)                                   \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                                   \
  X(PFNGLNAMEDBUFFERDATAPROC, NamedBufferData)                               \
  X(PFNGLCREATEVERTEXARRAYSPROC, CreateVertexArrays)                         \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                         \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                               \
  X(PFNGLVERTEXARRAYVERTEXBUFFERPROC, VertexArrayVertexBuffer)               \
  X(PFNGLVERTEXARRAYATTRIBFORMATPROC, VertexArrayAttribFormat)               \
  X(PFNGLVERTEXARRAYATTRIBBINDINGPROC, VertexArrayAttribBinding)             \
  X(PFNGLENABLEVERTEXARRAYATTRIBPROC, EnableVertexArrayAttrib)               \
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
  X(PFNGLPROGRAMUNIFORM1IPROC, ProgramUniform1i)                             \
  X(PFNGLPROGRAMUNIFORM1FPROC, ProgramUniform1f)                             \
  X(PFNGLPROGRAMUNIFORM2FPROC, ProgramUniform2f)                             \
  X(PFNGLPROGRAMUNIFORM3FPROC, ProgramUniform3f)                             \
  X(PFNGLPROGRAMUNIFORM4FPROC, ProgramUniform4f)                             \
  X(PFNGLPROGRAMUNIFORMMATRIX4FVPROC, ProgramUniformMatrix4fv)               \
  X(PFNGLCREATEQUERIESPROC, CreateQueries)                                   \
  X(PFNGLDELETEQUERIESPROC, DeleteQueries)                                   \
  X(PFNGLBEGINQUERYPROC, BeginQuery)                                         \
  X(PFNGLENDQUERYPROC, EndQuery)                                             \
  X(PFNGLGETQUERYOBJECTUI64VPROC, GetQueryObjectui64v)

typedef struct gs__gl_api {
#define GS__GL_MEMBER(type, name) type name;
  GS__GL_FUNCS(GS__GL_MEMBER)
#undef GS__GL_MEMBER
} gs__gl_api;

extern gs__gl_api gs__gl;

/* Drains the GL error queue. Returns SH_OK if it was empty, else
 * SH_ERR_DEVICE with a message naming `what` (the operation that was
 * running) and the GL error codes. */
sh_status gs__gl_check(const char *what, sh_error *err);

#define glGetError gs__gl.GetError
#define glGetString gs__gl.GetString
#define glGetIntegerv gs__gl.GetIntegerv
#define glFinish gs__gl.Finish
#define glEnable gs__gl.Enable
#define glDisable gs__gl.Disable
#define glBlendFunc gs__gl.BlendFunc
#define glBlendEquation gs__gl.BlendEquation
#define glDepthFunc gs__gl.DepthFunc
#define glDepthMask gs__gl.DepthMask
#define glViewport gs__gl.Viewport
#define glPolygonOffset gs__gl.PolygonOffset
#define glCullFace gs__gl.CullFace
#define glClipControl gs__gl.ClipControl
#define glReadPixels gs__gl.ReadPixels
#define glPixelStorei gs__gl.PixelStorei
#define glDrawArrays gs__gl.DrawArrays
#define glMultiDrawArrays gs__gl.MultiDrawArrays
#define glCreateTextures gs__gl.CreateTextures
#define glDeleteTextures gs__gl.DeleteTextures
#define glTextureStorage2D gs__gl.TextureStorage2D
#define glTextureStorage3D gs__gl.TextureStorage3D
#define glTextureSubImage2D gs__gl.TextureSubImage2D
#define glTextureSubImage3D gs__gl.TextureSubImage3D
#define glTextureParameteri gs__gl.TextureParameteri
#define glTextureParameterfv gs__gl.TextureParameterfv
#define glBindTextureUnit gs__gl.BindTextureUnit
#define glCreateFramebuffers gs__gl.CreateFramebuffers
#define glDeleteFramebuffers gs__gl.DeleteFramebuffers
#define glNamedFramebufferTexture gs__gl.NamedFramebufferTexture
#define glNamedFramebufferTextureLayer gs__gl.NamedFramebufferTextureLayer
#define glNamedFramebufferDrawBuffers gs__gl.NamedFramebufferDrawBuffers
#define glNamedFramebufferDrawBuffer gs__gl.NamedFramebufferDrawBuffer
#define glNamedFramebufferReadBuffer gs__gl.NamedFramebufferReadBuffer
#define glCheckNamedFramebufferStatus gs__gl.CheckNamedFramebufferStatus
#define glClearNamedFramebufferfv gs__gl.ClearNamedFramebufferfv
#define glBindFramebuffer gs__gl.BindFramebuffer
#define glCreateBuffers gs__gl.CreateBuffers
#define glDeleteBuffers gs__gl.DeleteBuffers
#define glNamedBufferData gs__gl.NamedBufferData
#define glCreateVertexArrays gs__gl.CreateVertexArrays
#define glDeleteVertexArrays gs__gl.DeleteVertexArrays
#define glBindVertexArray gs__gl.BindVertexArray
#define glVertexArrayVertexBuffer gs__gl.VertexArrayVertexBuffer
#define glVertexArrayAttribFormat gs__gl.VertexArrayAttribFormat
#define glVertexArrayAttribBinding gs__gl.VertexArrayAttribBinding
#define glEnableVertexArrayAttrib gs__gl.EnableVertexArrayAttrib
#define glCreateShader gs__gl.CreateShader
#define glShaderSource gs__gl.ShaderSource
#define glCompileShader gs__gl.CompileShader
#define glGetShaderiv gs__gl.GetShaderiv
#define glGetShaderInfoLog gs__gl.GetShaderInfoLog
#define glDeleteShader gs__gl.DeleteShader
#define glCreateProgram gs__gl.CreateProgram
#define glAttachShader gs__gl.AttachShader
#define glLinkProgram gs__gl.LinkProgram
#define glGetProgramiv gs__gl.GetProgramiv
#define glGetProgramInfoLog gs__gl.GetProgramInfoLog
#define glDeleteProgram gs__gl.DeleteProgram
#define glUseProgram gs__gl.UseProgram
#define glGetUniformLocation gs__gl.GetUniformLocation
#define glProgramUniform1i gs__gl.ProgramUniform1i
#define glProgramUniform1f gs__gl.ProgramUniform1f
#define glProgramUniform2f gs__gl.ProgramUniform2f
#define glProgramUniform3f gs__gl.ProgramUniform3f
#define glProgramUniform4f gs__gl.ProgramUniform4f
#define glProgramUniformMatrix4fv gs__gl.ProgramUniformMatrix4fv
#define glCreateQueries gs__gl.CreateQueries
#define glDeleteQueries gs__gl.DeleteQueries
#define glBeginQuery gs__gl.BeginQuery
#define glEndQuery gs__gl.EndQuery
#define glGetQueryObjectui64v gs__gl.GetQueryObjectui64v

#endif
