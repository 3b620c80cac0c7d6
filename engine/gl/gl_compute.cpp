// gl_compute.cpp: compile and link one compute shader, with the driver's info log in the error.
#include "gl/gl_compute.hpp"

#include <algorithm>
#include <vector>

namespace idk::gl {
namespace {

std::string shaderLog(const Api& api, GLuint shader) {
    GLint length = 0;
    api.glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::vector<char> log(size_t(std::max(length, 1)), '\0');
    api.glGetShaderInfoLog(shader, GLsizei(log.size()), nullptr, log.data());
    return log.data();
}

std::string programLog(const Api& api, GLuint program) {
    GLint length = 0;
    api.glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::vector<char> log(size_t(std::max(length, 1)), '\0');
    api.glGetProgramInfoLog(program, GLsizei(log.size()), nullptr, log.data());
    return log.data();
}

}  // namespace

ComputeProgram::ComputeProgram(const GlContext& gl, const std::string& name, const std::string& source)
    : gl_(gl), name_(name) {
    const Api& api = gl.api();
    GLuint shader = api.glCreateShader(GL_COMPUTE_SHADER);
    const char* text = source.c_str();
    api.glShaderSource(shader, 1, &text, nullptr);
    api.glCompileShader(shader);
    GLint ok = GL_FALSE;
    api.glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        const std::string log = shaderLog(api, shader);
        api.glDeleteShader(shader);
        throw GlError("OpenGL: compute shader '" + name + "' does not compile: " + log);
    }
    program_ = api.glCreateProgram();
    api.glAttachShader(program_, shader);
    api.glLinkProgram(program_);
    api.glDeleteShader(shader);  // flagged; freed with the program
    api.glGetProgramiv(program_, GL_LINK_STATUS, &ok);
    if (!ok) {
        const std::string log = programLog(api, program_);
        api.glDeleteProgram(program_);
        throw GlError("OpenGL: compute program '" + name + "' does not link: " + log);
    }
    gl.check("building compute program '" + name + "'");
}

ComputeProgram::~ComputeProgram() { gl_.api().glDeleteProgram(program_); }

void ComputeProgram::setUint(const char* uniform, GLuint value) const {
    const GLint location = gl_.api().glGetUniformLocation(program_, uniform);
    if (location < 0) throw GlError("OpenGL: program '" + name_ + "' has no uniform '" + uniform + "'");
    gl_.api().glProgramUniform1ui(program_, location, value);
}

void ComputeProgram::dispatch(GLuint groupsX, GLuint groupsY, GLuint groupsZ) const {
    const Api& api = gl_.api();
    api.glUseProgram(program_);
    api.glDispatchCompute(groupsX, groupsY, groupsZ);
    api.glMemoryBarrier(GL_ALL_BARRIER_BITS);
    api.glUseProgram(0);
    gl_.check("dispatching '" + name_ + "'");
}

}  // namespace idk::gl
