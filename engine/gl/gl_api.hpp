// gl_api.hpp: the OpenGL entry points the GL-interop rung uses, loaded at run time through eglGetProcAddress
// (gl_context.cpp) so the engine has no link-time dependency on libEGL/libGL: a machine without them still runs
// every Vulkan rung, and the GL rung is reported absent with the reason. One X-macro list declares and loads them.
#pragma once
#include <GL/gl.h>
#include <GL/glext.h>

namespace idk::gl {

// X(name, type): every function a GlContext loads; a missing one makes the context unusable (named in the error).
// GL 1.x entry points have no PFN typedef in glext.h: their type is decltype of gl.h's declaration, which is never
// called directly, so nothing links against libGL.
#define IDK_GL_FUNCTIONS(X)                                                      \
    X(glGetString, decltype(&::glGetString))                                           \
    X(glGetStringi, PFNGLGETSTRINGIPROC)                                         \
    X(glGetIntegerv, decltype(&::glGetIntegerv))                                       \
    X(glGetError, decltype(&::glGetError))                                             \
    X(glFinish, decltype(&::glFinish))                                                 \
    X(glFlush, decltype(&::glFlush))                                                   \
    X(glCreateMemoryObjectsEXT, PFNGLCREATEMEMORYOBJECTSEXTPROC)                 \
    X(glDeleteMemoryObjectsEXT, PFNGLDELETEMEMORYOBJECTSEXTPROC)                 \
    X(glMemoryObjectParameterivEXT, PFNGLMEMORYOBJECTPARAMETERIVEXTPROC)         \
    X(glImportMemoryFdEXT, PFNGLIMPORTMEMORYFDEXTPROC)                           \
    X(glGetUnsignedBytevEXT, PFNGLGETUNSIGNEDBYTEVEXTPROC)                       \
    X(glCreateTextures, PFNGLCREATETEXTURESPROC)                                 \
    X(glDeleteTextures, decltype(&::glDeleteTextures))                                 \
    X(glTextureStorageMem2DEXT, PFNGLTEXTURESTORAGEMEM2DEXTPROC)                 \
    X(glGetTextureImage, PFNGLGETTEXTUREIMAGEPROC)                               \
    X(glTextureSubImage2D, PFNGLTEXTURESUBIMAGE2DPROC)                           \
    X(glTextureStorage3D, PFNGLTEXTURESTORAGE3DPROC)                             \
    X(glClearTexImage, PFNGLCLEARTEXIMAGEPROC)                                   \
    X(glClearTexSubImage, PFNGLCLEARTEXSUBIMAGEPROC)                             \
    X(glNamedBufferStorage, PFNGLNAMEDBUFFERSTORAGEPROC)                         \
    X(glClearNamedBufferData, PFNGLCLEARNAMEDBUFFERDATAPROC)                     \
    X(glCreateBuffers, PFNGLCREATEBUFFERSPROC)                                   \
    X(glDeleteBuffers, PFNGLDELETEBUFFERSPROC)                                   \
    X(glNamedBufferStorageMemEXT, PFNGLNAMEDBUFFERSTORAGEMEMEXTPROC)             \
    X(glGetNamedBufferSubData, PFNGLGETNAMEDBUFFERSUBDATAPROC)                   \
    X(glNamedBufferSubData, PFNGLNAMEDBUFFERSUBDATAPROC)                         \
    X(glCreateShader, PFNGLCREATESHADERPROC)                                     \
    X(glShaderSource, PFNGLSHADERSOURCEPROC)                                     \
    X(glCompileShader, PFNGLCOMPILESHADERPROC)                                   \
    X(glGetShaderiv, PFNGLGETSHADERIVPROC)                                       \
    X(glGetShaderInfoLog, PFNGLGETSHADERINFOLOGPROC)                             \
    X(glDeleteShader, PFNGLDELETESHADERPROC)                                     \
    X(glCreateProgram, PFNGLCREATEPROGRAMPROC)                                   \
    X(glAttachShader, PFNGLATTACHSHADERPROC)                                     \
    X(glLinkProgram, PFNGLLINKPROGRAMPROC)                                       \
    X(glGetProgramiv, PFNGLGETPROGRAMIVPROC)                                     \
    X(glGetProgramInfoLog, PFNGLGETPROGRAMINFOLOGPROC)                           \
    X(glDeleteProgram, PFNGLDELETEPROGRAMPROC)                                   \
    X(glUseProgram, PFNGLUSEPROGRAMPROC)                                         \
    X(glProgramUniform1ui, PFNGLPROGRAMUNIFORM1UIPROC)                           \
    X(glGetUniformLocation, PFNGLGETUNIFORMLOCATIONPROC)                         \
    X(glBindBufferBase, PFNGLBINDBUFFERBASEPROC)                                 \
    X(glBindImageTexture, PFNGLBINDIMAGETEXTUREPROC)                             \
    X(glDispatchCompute, PFNGLDISPATCHCOMPUTEPROC)                               \
    X(glMemoryBarrier, PFNGLMEMORYBARRIERPROC)

// X(name, type): GL_EXT_semaphore / GL_EXT_semaphore_fd, loaded when present and left null otherwise: without them
// the rung still runs, ordering the two APIs with CPU-side waits (gl_sync.hpp chooses).
#define IDK_GL_SEMAPHORE_FUNCTIONS(X)                                            \
    X(glGenSemaphoresEXT, PFNGLGENSEMAPHORESEXTPROC)                             \
    X(glDeleteSemaphoresEXT, PFNGLDELETESEMAPHORESEXTPROC)                       \
    X(glImportSemaphoreFdEXT, PFNGLIMPORTSEMAPHOREFDEXTPROC)                     \
    X(glWaitSemaphoreEXT, PFNGLWAITSEMAPHOREEXTPROC)                             \
    X(glSignalSemaphoreEXT, PFNGLSIGNALSEMAPHOREEXTPROC)

struct Api {
#define IDK_GL_DECLARE(name, type) type name = nullptr;
    IDK_GL_FUNCTIONS(IDK_GL_DECLARE)
    IDK_GL_SEMAPHORE_FUNCTIONS(IDK_GL_DECLARE)
#undef IDK_GL_DECLARE
    bool hasSemaphoreFunctions() const noexcept {
        return glGenSemaphoresEXT && glDeleteSemaphoresEXT && glImportSemaphoreFdEXT && glWaitSemaphoreEXT &&
               glSignalSemaphoreEXT;
    }
};

}  // namespace idk::gl
