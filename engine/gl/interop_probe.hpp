// interop_probe.hpp: the GL-interop rung's start-up probe. It creates the headless GL context, checks the
// extensions the rung needs (GL_EXT_memory_object_fd; GL_NV_shader_atomic_float and
// GL_NV_shader_atomic_fp16_vector for the ladders that use them; GL_EXT_semaphore_fd, else CPU-side waits: the
// context's sync(), gl_sync.hpp), that
// GL runs on the Vulkan device (matching UUIDs), and that a small image and a buffer survive a round trip:
// written by Vulkan, read and rewritten by GL, read back by Vulkan, exact.
#pragma once
#include <memory>
#include <string>

#include "gl/gl_context.hpp"

namespace idk::vk {
class Context;
}

namespace idk::gl {

struct ProbeResult {
    std::unique_ptr<GlContext> context;  // null when the rung is unavailable
    bool atomicFloat = false;            // GL_NV_shader_atomic_float
    bool atomicFp16Vector = false;       // GL_NV_shader_atomic_fp16_vector
    bool semaphoreFd = false;            // GL_EXT_semaphore_fd
    std::string note;                    // why unavailable, or what was found (renderer, platform, sync mode)
};

// Never throws for a missing or broken GL: the reason goes to note.
ProbeResult probeGlInterop(vk::Context& ctx);

// The round trip of the probe (also used by tests): an RGBA8 image and a uint buffer written by Vulkan, checked
// and overwritten by GL (glGetTextureImage / glTextureSubImage2D, glGetNamedBufferSubData / glNamedBufferSubData),
// read back by Vulkan. Empty on success, else what differed.
std::string roundTrip(vk::Context& ctx, const GlContext& gl, uint32_t width, uint32_t height);

}  // namespace idk::gl
