// gl_compute.hpp: an OpenGL compute program (GLSL 4.50 source compiled by the GL driver at run time) and its
// dispatch, for GL-interop passes: the steps that need a GL-only extension (GL_NV_shader_atomic_float, ...) run
// on shared buffers and images (shared_memory.hpp). Call everything inside a GlContext::Current scope.
#pragma once
#include <string>

#include "gl/gl_context.hpp"

namespace idk::gl {

class ComputeProgram {
public:
    // Throws GlError with the driver's log and `name` when the source does not compile or link.
    ComputeProgram(const GlContext& gl, const std::string& name, const std::string& source);
    ~ComputeProgram();
    ComputeProgram(const ComputeProgram&) = delete;
    ComputeProgram& operator=(const ComputeProgram&) = delete;

    GLuint id() const noexcept { return program_; }
    void setUint(const char* uniform, GLuint value) const;  // a `uniform uint` of the program
    // glDispatchCompute, then a barrier making its storage writes visible to GL reads that follow (glFinish is
    // still needed before Vulkan reads them: finishGl).
    void dispatch(GLuint groupsX, GLuint groupsY = 1, GLuint groupsZ = 1) const;

private:
    const GlContext& gl_;
    std::string name_;
    GLuint program_ = 0;
};

}  // namespace idk::gl
