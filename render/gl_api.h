// The OpenGL 4.5 core entry points occsim uses, loaded at run time from whichever context is
// current (EGL, OSMesa or GLFW), so that one renderer serves them all without linking libGL
// directly. Code calls them by their usual names; the macros below route those names to our
// pointers.
#pragma once

#include <GL/glcorearb.h>

#include <string>

#include "render/gl_loader.h"

// X(PFN type, name) for every function we call.
#define OCCSIM_GL_FUNCTIONS(X)                                         \
    X(PFNGLGETSTRINGPROC, glGetString)                                 \
    X(PFNGLGETSTRINGIPROC, glGetStringi)                               \
    X(PFNGLGETINTEGERVPROC, glGetIntegerv)                             \
    X(PFNGLGETERRORPROC, glGetError)                                   \
    X(PFNGLENABLEPROC, glEnable)                                       \
    X(PFNGLDISABLEPROC, glDisable)                                     \
    X(PFNGLVIEWPORTPROC, glViewport)                                   \
    X(PFNGLCLEARBUFFERFVPROC, glClearBufferfv)                         \
    X(PFNGLCLEARBUFFERUIVPROC, glClearBufferuiv)                       \
    X(PFNGLDEPTHFUNCPROC, glDepthFunc)                                 \
    X(PFNGLDEPTHMASKPROC, glDepthMask)                                 \
    X(PFNGLCOLORMASKPROC, glColorMask)                                 \
    X(PFNGLCOLORMASKIPROC, glColorMaski)                               \
    X(PFNGLCULLFACEPROC, glCullFace)                                   \
    X(PFNGLCLIPCONTROLPROC, glClipControl)                             \
    X(PFNGLFINISHPROC, glFinish)                                       \
    X(PFNGLFLUSHPROC, glFlush)                                         \
    X(PFNGLREADPIXELSPROC, glReadPixels)                               \
    X(PFNGLREADBUFFERPROC, glReadBuffer)                               \
    X(PFNGLPIXELSTOREIPROC, glPixelStorei)                             \
    X(PFNGLDRAWBUFFERSPROC, glDrawBuffers)                             \
    X(PFNGLGENFRAMEBUFFERSPROC, glGenFramebuffers)                     \
    X(PFNGLDELETEFRAMEBUFFERSPROC, glDeleteFramebuffers)               \
    X(PFNGLBINDFRAMEBUFFERPROC, glBindFramebuffer)                     \
    X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, glFramebufferRenderbuffer)     \
    X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, glCheckFramebufferStatus)       \
    X(PFNGLBLITFRAMEBUFFERPROC, glBlitFramebuffer)                     \
    X(PFNGLFRAMEBUFFERTEXTURE2DPROC, glFramebufferTexture2D)           \
    X(PFNGLGENTEXTURESPROC, glGenTextures)                             \
    X(PFNGLDELETETEXTURESPROC, glDeleteTextures)                       \
    X(PFNGLBINDTEXTUREPROC, glBindTexture)                             \
    X(PFNGLTEXIMAGE2DPROC, glTexImage2D)                               \
    X(PFNGLGENRENDERBUFFERSPROC, glGenRenderbuffers)                   \
    X(PFNGLDELETERENDERBUFFERSPROC, glDeleteRenderbuffers)             \
    X(PFNGLBINDRENDERBUFFERPROC, glBindRenderbuffer)                   \
    X(PFNGLRENDERBUFFERSTORAGEPROC, glRenderbufferStorage)             \
    X(PFNGLGENBUFFERSPROC, glGenBuffers)                               \
    X(PFNGLDELETEBUFFERSPROC, glDeleteBuffers)                         \
    X(PFNGLBINDBUFFERPROC, glBindBuffer)                               \
    X(PFNGLBUFFERDATAPROC, glBufferData)                               \
    X(PFNGLGENVERTEXARRAYSPROC, glGenVertexArrays)                     \
    X(PFNGLDELETEVERTEXARRAYSPROC, glDeleteVertexArrays)               \
    X(PFNGLBINDVERTEXARRAYPROC, glBindVertexArray)                     \
    X(PFNGLENABLEVERTEXATTRIBARRAYPROC, glEnableVertexAttribArray)     \
    X(PFNGLVERTEXATTRIBPOINTERPROC, glVertexAttribPointer)             \
    X(PFNGLDRAWELEMENTSBASEVERTEXPROC, glDrawElementsBaseVertex)       \
    X(PFNGLDRAWELEMENTSPROC, glDrawElements)                           \
    X(PFNGLCREATESHADERPROC, glCreateShader)                           \
    X(PFNGLSHADERSOURCEPROC, glShaderSource)                           \
    X(PFNGLCOMPILESHADERPROC, glCompileShader)                         \
    X(PFNGLGETSHADERIVPROC, glGetShaderiv)                             \
    X(PFNGLGETSHADERINFOLOGPROC, glGetShaderInfoLog)                   \
    X(PFNGLDELETESHADERPROC, glDeleteShader)                           \
    X(PFNGLCREATEPROGRAMPROC, glCreateProgram)                         \
    X(PFNGLATTACHSHADERPROC, glAttachShader)                           \
    X(PFNGLLINKPROGRAMPROC, glLinkProgram)                             \
    X(PFNGLGETPROGRAMIVPROC, glGetProgramiv)                           \
    X(PFNGLGETPROGRAMINFOLOGPROC, glGetProgramInfoLog)                 \
    X(PFNGLDELETEPROGRAMPROC, glDeleteProgram)                         \
    X(PFNGLUSEPROGRAMPROC, glUseProgram)                               \
    X(PFNGLGETUNIFORMLOCATIONPROC, glGetUniformLocation)               \
    X(PFNGLUNIFORMMATRIX4FVPROC, glUniformMatrix4fv)                   \
    X(PFNGLUNIFORM3FVPROC, glUniform3fv)                               \
    X(PFNGLUNIFORM1UIPROC, glUniform1ui)                               \
    X(PFNGLGENQUERIESPROC, glGenQueries)                               \
    X(PFNGLDELETEQUERIESPROC, glDeleteQueries)                         \
    X(PFNGLBEGINQUERYPROC, glBeginQuery)                               \
    X(PFNGLENDQUERYPROC, glEndQuery)                                   \
    X(PFNGLBEGINCONDITIONALRENDERPROC, glBeginConditionalRender)       \
    X(PFNGLENDCONDITIONALRENDERPROC, glEndConditionalRender)           \
    X(PFNGLGETQUERYOBJECTUIVPROC, glGetQueryObjectuiv)                 \
    X(PFNGLGETQUERYOBJECTUI64VPROC, glGetQueryObjectui64v)             \
    X(PFNGLDISPATCHCOMPUTEPROC, glDispatchCompute)                     \
    X(PFNGLMEMORYBARRIERPROC, glMemoryBarrier)                         \
    X(PFNGLBINDIMAGETEXTUREPROC, glBindImageTexture)                   \
    X(PFNGLCOPYIMAGESUBDATAPROC, glCopyImageSubData)                   \
    X(PFNGLTEXSTORAGE2DPROC, glTexStorage2D)                           \
    X(PFNGLTEXPARAMETERIPROC, glTexParameteri)                         \
    X(PFNGLACTIVETEXTUREPROC, glActiveTexture)                         \
    X(PFNGLBINDBUFFERBASEPROC, glBindBufferBase)                       \
    X(PFNGLGETBUFFERSUBDATAPROC, glGetBufferSubData)                   \
    X(PFNGLBUFFERSUBDATAPROC, glBufferSubData)                         \
    X(PFNGLUNIFORM1IPROC, glUniform1i)                                 \
    X(PFNGLVERTEXATTRIBDIVISORPROC, glVertexAttribDivisor)             \
    X(PFNGLVERTEXATTRIBIPOINTERPROC, glVertexAttribIPointer)           \
    X(PFNGLDRAWELEMENTSINSTANCEDBASEVERTEXBASEINSTANCEPROC,            \
      glDrawElementsInstancedBaseVertexBaseInstance)                   \
    X(PFNGLDRAWELEMENTSINSTANCEDPROC, glDrawElementsInstanced)         \
    X(PFNGLMULTIDRAWELEMENTSINDIRECTPROC, glMultiDrawElementsIndirect) \
    X(PFNGLCLEARBUFFERSUBDATAPROC, glClearBufferSubData)               \
    X(PFNGLCOPYBUFFERSUBDATAPROC, glCopyBufferSubData)                 \
    X(PFNGLQUERYCOUNTERPROC, glQueryCounter)                           \
    X(PFNGLUNIFORM1FPROC, glUniform1f)                                 \
    X(PFNGLUNIFORM2IPROC, glUniform2i)

#define OCCSIM_GL_DECLARE(type, name) extern type occsim_##name;
extern "C" {
OCCSIM_GL_FUNCTIONS(OCCSIM_GL_DECLARE)
}
#undef OCCSIM_GL_DECLARE

#define glGetString occsim_glGetString
#define glGetStringi occsim_glGetStringi
#define glGetIntegerv occsim_glGetIntegerv
#define glGetError occsim_glGetError
#define glEnable occsim_glEnable
#define glDisable occsim_glDisable
#define glViewport occsim_glViewport
#define glClearBufferfv occsim_glClearBufferfv
#define glClearBufferuiv occsim_glClearBufferuiv
#define glDepthFunc occsim_glDepthFunc
#define glDepthMask occsim_glDepthMask
#define glColorMask occsim_glColorMask
#define glColorMaski occsim_glColorMaski
#define glCullFace occsim_glCullFace
#define glClipControl occsim_glClipControl
#define glFinish occsim_glFinish
#define glFlush occsim_glFlush
#define glReadPixels occsim_glReadPixels
#define glReadBuffer occsim_glReadBuffer
#define glPixelStorei occsim_glPixelStorei
#define glDrawBuffers occsim_glDrawBuffers
#define glGenFramebuffers occsim_glGenFramebuffers
#define glDeleteFramebuffers occsim_glDeleteFramebuffers
#define glBindFramebuffer occsim_glBindFramebuffer
#define glFramebufferRenderbuffer occsim_glFramebufferRenderbuffer
#define glCheckFramebufferStatus occsim_glCheckFramebufferStatus
#define glBlitFramebuffer occsim_glBlitFramebuffer
#define glFramebufferTexture2D occsim_glFramebufferTexture2D
#define glGenTextures occsim_glGenTextures
#define glDeleteTextures occsim_glDeleteTextures
#define glBindTexture occsim_glBindTexture
#define glTexImage2D occsim_glTexImage2D
#define glGenRenderbuffers occsim_glGenRenderbuffers
#define glDeleteRenderbuffers occsim_glDeleteRenderbuffers
#define glBindRenderbuffer occsim_glBindRenderbuffer
#define glRenderbufferStorage occsim_glRenderbufferStorage
#define glGenBuffers occsim_glGenBuffers
#define glDeleteBuffers occsim_glDeleteBuffers
#define glBindBuffer occsim_glBindBuffer
#define glBufferData occsim_glBufferData
#define glGenVertexArrays occsim_glGenVertexArrays
#define glDeleteVertexArrays occsim_glDeleteVertexArrays
#define glBindVertexArray occsim_glBindVertexArray
#define glEnableVertexAttribArray occsim_glEnableVertexAttribArray
#define glVertexAttribPointer occsim_glVertexAttribPointer
#define glDrawElementsBaseVertex occsim_glDrawElementsBaseVertex
#define glDrawElements occsim_glDrawElements
#define glCreateShader occsim_glCreateShader
#define glShaderSource occsim_glShaderSource
#define glCompileShader occsim_glCompileShader
#define glGetShaderiv occsim_glGetShaderiv
#define glGetShaderInfoLog occsim_glGetShaderInfoLog
#define glDeleteShader occsim_glDeleteShader
#define glCreateProgram occsim_glCreateProgram
#define glAttachShader occsim_glAttachShader
#define glLinkProgram occsim_glLinkProgram
#define glGetProgramiv occsim_glGetProgramiv
#define glGetProgramInfoLog occsim_glGetProgramInfoLog
#define glDeleteProgram occsim_glDeleteProgram
#define glUseProgram occsim_glUseProgram
#define glGetUniformLocation occsim_glGetUniformLocation
#define glUniformMatrix4fv occsim_glUniformMatrix4fv
#define glUniform3fv occsim_glUniform3fv
#define glUniform1ui occsim_glUniform1ui
#define glGenQueries occsim_glGenQueries
#define glDeleteQueries occsim_glDeleteQueries
#define glBeginQuery occsim_glBeginQuery
#define glEndQuery occsim_glEndQuery
#define glBeginConditionalRender occsim_glBeginConditionalRender
#define glEndConditionalRender occsim_glEndConditionalRender
#define glGetQueryObjectuiv occsim_glGetQueryObjectuiv
#define glGetQueryObjectui64v occsim_glGetQueryObjectui64v
#define glDispatchCompute occsim_glDispatchCompute
#define glMemoryBarrier occsim_glMemoryBarrier
#define glBindImageTexture occsim_glBindImageTexture
#define glCopyImageSubData occsim_glCopyImageSubData
#define glTexStorage2D occsim_glTexStorage2D
#define glTexParameteri occsim_glTexParameteri
#define glActiveTexture occsim_glActiveTexture
#define glBindBufferBase occsim_glBindBufferBase
#define glGetBufferSubData occsim_glGetBufferSubData
#define glBufferSubData occsim_glBufferSubData
#define glUniform1i occsim_glUniform1i
#define glUniform2i occsim_glUniform2i
#define glVertexAttribDivisor occsim_glVertexAttribDivisor
#define glVertexAttribIPointer occsim_glVertexAttribIPointer
#define glDrawElementsInstancedBaseVertexBaseInstance \
    occsim_glDrawElementsInstancedBaseVertexBaseInstance
#define glDrawElementsInstanced occsim_glDrawElementsInstanced
#define glMultiDrawElementsIndirect occsim_glMultiDrawElementsIndirect
#define glClearBufferSubData occsim_glClearBufferSubData
#define glCopyBufferSubData occsim_glCopyBufferSubData
#define glQueryCounter occsim_glQueryCounter
#define glUniform1f occsim_glUniform1f

namespace occsim {

// Throws std::runtime_error naming `what` (the GL call) and the error code when glGetError() is
// set. Used after set-up calls, not in the per-draw hot path.
void checkGl(const char* what);

}  // namespace occsim

#define OCCSIM_GL_CHECK(call)     \
    do {                          \
        call;                     \
        ::occsim::checkGl(#call); \
    } while (0)
