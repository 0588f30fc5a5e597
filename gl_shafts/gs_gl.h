/* The OpenGL 4.5 core entry points gl_shafts uses, one table per GL context
 * (gs_context.h loads it through the backend's GetProcAddress: EGL's or
 * OSMesa's), and the check that turns GL errors into sh_error reports.
 *
 * Every file that calls GL includes this header instead of <GL/gl.h>: the
 * names below (glClear, glCreateTextures, ...) are macros that call through
 * the table of the context current on the calling thread (gs__gl_current,
 * a thread-local pointer that gs__context_make_current sets), so code reads
 * like ordinary GL. Calling GL with no gl_shafts context current on the
 * thread is a bug (a NULL dereference). A GL function missing from the
 * table fails to compile (it has no prototype), so the table and the code
 * cannot drift apart silently. */
#ifndef GS_GL_H
#define GS_GL_H

#include <GL/glcorearb.h>
#include <stddef.h>

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
  X(PFNGLSCISSORPROC, Scissor)                                               \
  X(PFNGLCOLORMASKPROC, ColorMask)                                           \
  X(PFNGLPOLYGONOFFSETPROC, PolygonOffset)                                   \
  X(PFNGLBINDBUFFERBASEPROC, BindBufferBase)                                 \
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
  X(PFNGLCREATESAMPLERSPROC, CreateSamplers)                                 \
  X(PFNGLDELETESAMPLERSPROC, DeleteSamplers)                                 \
  X(PFNGLSAMPLERPARAMETERIPROC, SamplerParameteri)                           \
  X(PFNGLSAMPLERPARAMETERFVPROC, SamplerParameterfv)                         \
  X(PFNGLBINDSAMPLERPROC, BindSampler)                                       \
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
  X(PFNGLNAMEDBUFFERSUBDATAPROC, NamedBufferSubData)                         \
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
  X(PFNGLPROGRAMPARAMETERIPROC, ProgramParameteri)                           \
  X(PFNGLGETPROGRAMBINARYPROC, GetProgramBinary)                             \
  X(PFNGLPROGRAMBINARYPROC, ProgramBinary)                                   \
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

/* The table of the gl_shafts context current on this thread, NULL if none. */
extern _Thread_local const gs__gl_api *gs__gl_current;

/* Looks a GL function up by name ("glClear"); NULL if it does not exist. */
typedef void (*gs__gl_proc)(void);
typedef gs__gl_proc (*gs__gl_getproc)(void *user, const char *name);

/* Fills `api` through getproc(user, name). Returns SH_ERR_DEVICE naming the
 * first missing function. */
sh_status gs__gl_load(gs__gl_getproc getproc, void *user, gs__gl_api *api,
                      sh_error *err);

/* Sets the context-wide state gl_shafts relies on (depth in [0, 1] for
 * reversed-Z) and copies the GL_RENDERER, GL_VENDOR and GL_VERSION strings.
 * Call with the context current and its table in gs__gl_current. */
sh_status gs__gl_setup(char *renderer, size_t renderer_size, char *vendor,
                       size_t vendor_size, char *version, size_t version_size,
                       sh_error *err);

/* Drains the GL error queue. Returns SH_OK if it was empty, else
 * SH_ERR_DEVICE with a message naming `what` (the operation that was
 * running) and the GL error codes. */
sh_status gs__gl_check(const char *what, sh_error *err);

/* Waits for GL's work (glFinish) and returns the seconds since *t, which
 * it sets to now (sh_seconds): a stage's time, its shaders' included. */
double gs__gl_lap(double *t);

#define glGetError gs__gl_current->GetError
#define glGetString gs__gl_current->GetString
#define glGetIntegerv gs__gl_current->GetIntegerv
#define glFinish gs__gl_current->Finish
#define glEnable gs__gl_current->Enable
#define glDisable gs__gl_current->Disable
#define glBlendFunc gs__gl_current->BlendFunc
#define glBlendEquation gs__gl_current->BlendEquation
#define glDepthFunc gs__gl_current->DepthFunc
#define glDepthMask gs__gl_current->DepthMask
#define glViewport gs__gl_current->Viewport
#define glScissor gs__gl_current->Scissor
#define glColorMask gs__gl_current->ColorMask
#define glPolygonOffset gs__gl_current->PolygonOffset
#define glBindBufferBase gs__gl_current->BindBufferBase
#define glCullFace gs__gl_current->CullFace
#define glClipControl gs__gl_current->ClipControl
#define glReadPixels gs__gl_current->ReadPixels
#define glPixelStorei gs__gl_current->PixelStorei
#define glDrawArrays gs__gl_current->DrawArrays
#define glMultiDrawArrays gs__gl_current->MultiDrawArrays
#define glCreateTextures gs__gl_current->CreateTextures
#define glDeleteTextures gs__gl_current->DeleteTextures
#define glTextureStorage2D gs__gl_current->TextureStorage2D
#define glTextureStorage3D gs__gl_current->TextureStorage3D
#define glTextureSubImage2D gs__gl_current->TextureSubImage2D
#define glTextureSubImage3D gs__gl_current->TextureSubImage3D
#define glTextureParameteri gs__gl_current->TextureParameteri
#define glTextureParameterfv gs__gl_current->TextureParameterfv
#define glBindTextureUnit gs__gl_current->BindTextureUnit
#define glCreateFramebuffers gs__gl_current->CreateFramebuffers
#define glCreateSamplers gs__gl_current->CreateSamplers
#define glDeleteSamplers gs__gl_current->DeleteSamplers
#define glSamplerParameteri gs__gl_current->SamplerParameteri
#define glSamplerParameterfv gs__gl_current->SamplerParameterfv
#define glBindSampler gs__gl_current->BindSampler
#define glDeleteFramebuffers gs__gl_current->DeleteFramebuffers
#define glNamedFramebufferTexture gs__gl_current->NamedFramebufferTexture
#define glNamedFramebufferTextureLayer gs__gl_current->NamedFramebufferTextureLayer
#define glNamedFramebufferDrawBuffers gs__gl_current->NamedFramebufferDrawBuffers
#define glNamedFramebufferDrawBuffer gs__gl_current->NamedFramebufferDrawBuffer
#define glNamedFramebufferReadBuffer gs__gl_current->NamedFramebufferReadBuffer
#define glCheckNamedFramebufferStatus gs__gl_current->CheckNamedFramebufferStatus
#define glClearNamedFramebufferfv gs__gl_current->ClearNamedFramebufferfv
#define glBindFramebuffer gs__gl_current->BindFramebuffer
#define glCreateBuffers gs__gl_current->CreateBuffers
#define glDeleteBuffers gs__gl_current->DeleteBuffers
#define glNamedBufferData gs__gl_current->NamedBufferData
#define glNamedBufferSubData gs__gl_current->NamedBufferSubData
#define glCreateVertexArrays gs__gl_current->CreateVertexArrays
#define glDeleteVertexArrays gs__gl_current->DeleteVertexArrays
#define glBindVertexArray gs__gl_current->BindVertexArray
#define glVertexArrayVertexBuffer gs__gl_current->VertexArrayVertexBuffer
#define glVertexArrayAttribFormat gs__gl_current->VertexArrayAttribFormat
#define glVertexArrayAttribBinding gs__gl_current->VertexArrayAttribBinding
#define glEnableVertexArrayAttrib gs__gl_current->EnableVertexArrayAttrib
#define glCreateShader gs__gl_current->CreateShader
#define glShaderSource gs__gl_current->ShaderSource
#define glCompileShader gs__gl_current->CompileShader
#define glGetShaderiv gs__gl_current->GetShaderiv
#define glGetShaderInfoLog gs__gl_current->GetShaderInfoLog
#define glDeleteShader gs__gl_current->DeleteShader
#define glCreateProgram gs__gl_current->CreateProgram
#define glAttachShader gs__gl_current->AttachShader
#define glLinkProgram gs__gl_current->LinkProgram
#define glGetProgramiv gs__gl_current->GetProgramiv
#define glGetProgramInfoLog gs__gl_current->GetProgramInfoLog
#define glDeleteProgram gs__gl_current->DeleteProgram
#define glProgramParameteri gs__gl_current->ProgramParameteri
#define glGetProgramBinary gs__gl_current->GetProgramBinary
#define glProgramBinary gs__gl_current->ProgramBinary
#define glUseProgram gs__gl_current->UseProgram
#define glGetUniformLocation gs__gl_current->GetUniformLocation
#define glProgramUniform1i gs__gl_current->ProgramUniform1i
#define glProgramUniform1f gs__gl_current->ProgramUniform1f
#define glProgramUniform2f gs__gl_current->ProgramUniform2f
#define glProgramUniform3f gs__gl_current->ProgramUniform3f
#define glProgramUniform4f gs__gl_current->ProgramUniform4f
#define glProgramUniformMatrix4fv gs__gl_current->ProgramUniformMatrix4fv
#define glCreateQueries gs__gl_current->CreateQueries
#define glDeleteQueries gs__gl_current->DeleteQueries
#define glBeginQuery gs__gl_current->BeginQuery
#define glEndQuery gs__gl_current->EndQuery
#define glGetQueryObjectui64v gs__gl_current->GetQueryObjectui64v

#endif
