// interop_probe.cpp: see interop_probe.hpp. The round trip uses transfers on both sides (no shaders), so the
// probe costs a few milliseconds at start-up; the conformance check "gl-interop round trip" runs GL compute.
#include "gl/interop_probe.hpp"

#include <cstdlib>
#include <cstring>
#include <vector>

#include "gl/gl_sync.hpp"
#include "gl/shared_memory.hpp"
#include "vk/check.hpp"
#include "vk/context.hpp"
#include "vk/transfer.hpp"

namespace idk::gl {
namespace {

// Deterministic non-trivial bytes (no two neighbours equal, every bit position used).
std::vector<uint8_t> pattern(size_t bytes, uint32_t seed) {
    std::vector<uint8_t> v(bytes);
    uint32_t x = seed * 2654435761u + 1;
    for (uint8_t& b : v) {
        x ^= x << 13, x ^= x >> 17, x ^= x << 5;
        b = uint8_t(x);
    }
    return v;
}

std::string firstDifference(const std::vector<uint8_t>& got, const std::vector<uint8_t>& want, const std::string& what) {
    if (got.size() != want.size()) return what + ": " + std::to_string(got.size()) + " bytes, expected " + std::to_string(want.size());
    for (size_t i = 0; i < got.size(); ++i)
        if (got[i] != want[i])
            return what + ": byte " + std::to_string(i) + " is " + std::to_string(got[i]) + ", expected " + std::to_string(want[i]);
    return {};
}

bool sameUuids(const vk::Context& ctx, const GlContext& gl) {
    VkPhysicalDeviceIDProperties id{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ID_PROPERTIES};
    VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &id};
    vkGetPhysicalDeviceProperties2(ctx.physicalDevice(), &props);
    return gl.deviceUuid().size() == VK_UUID_SIZE && gl.driverUuid().size() == VK_UUID_SIZE &&
           std::memcmp(gl.deviceUuid().data(), id.deviceUUID, VK_UUID_SIZE) == 0 &&
           std::memcmp(gl.driverUuid().data(), id.driverUUID, VK_UUID_SIZE) == 0;
}

}  // namespace

std::string roundTrip(vk::Context& ctx, const GlContext& gl, uint32_t width, uint32_t height) {
    const size_t imageBytes = size_t(width) * height * 4, bufferBytes = 256;
    SharedImage image(ctx, gl, VK_FORMAT_R8G8B8A8_UNORM, width, height, VK_IMAGE_USAGE_STORAGE_BIT, "probe image");
    SharedBuffer buffer(ctx, gl, bufferBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "probe buffer");
    const std::vector<uint8_t> fromVk = pattern(imageBytes, 1), fromGl = pattern(imageBytes, 2);
    const std::vector<uint8_t> bufFromVk = pattern(bufferBytes, 3), bufFromGl = pattern(bufferBytes, 4);

    // Vulkan writes both and hands them to GL; runImmediate returns after the submission completed (CPU wait).
    vk::uploadImage(ctx, image.vk(), fromVk.data(), imageBytes, VK_IMAGE_LAYOUT_GENERAL);
    vk::uploadBuffer(ctx, buffer.vk(), bufFromVk.data(), bufferBytes);
    ctx.runImmediate([&](VkCommandBuffer cmd) {
        releaseToGl(cmd, ctx, image, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                    VK_ACCESS_2_TRANSFER_WRITE_BIT);
        releaseToGl(cmd, ctx, buffer, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    });

    std::string error;
    {
        GlContext::Current current(gl);
        const Api& api = gl.api();
        std::vector<uint8_t> seen(imageBytes), seenBuf(bufferBytes);
        api.glGetTextureImage(image.gl(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(imageBytes), seen.data());
        api.glGetNamedBufferSubData(buffer.gl(), 0, GLsizeiptr(bufferBytes), seenBuf.data());
        gl.check("reading the shared image and buffer");
        error = firstDifference(seen, fromVk, "GL read of the image Vulkan wrote");
        if (error.empty()) error = firstDifference(seenBuf, bufFromVk, "GL read of the buffer Vulkan wrote");
        api.glTextureSubImage2D(image.gl(), 0, 0, 0, GLsizei(width), GLsizei(height), GL_RGBA, GL_UNSIGNED_BYTE,
                                fromGl.data());
        api.glNamedBufferSubData(buffer.gl(), 0, GLsizeiptr(bufferBytes), bufFromGl.data());
        gl.check("writing the shared image and buffer");
        finishGl(gl);
    }
    ctx.runImmediate([&](VkCommandBuffer cmd) {
        acquireFromGl(cmd, ctx, image, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
        acquireFromGl(cmd, ctx, buffer, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    });
    if (!error.empty()) return error;
    error = firstDifference(vk::readbackImage(ctx, image.vk(), VK_IMAGE_LAYOUT_GENERAL), fromGl,
                            "Vulkan read of the image GL wrote");
    if (!error.empty()) return error;
    std::vector<uint8_t> back(bufferBytes);
    vk::downloadBuffer(ctx, buffer.vk(), back.data(), bufferBytes);
    return firstDifference(back, bufFromGl, "Vulkan read of the buffer GL wrote");
}

ProbeResult probeGlInterop(vk::Context& ctx) {
    ProbeResult r;
    if (!ctx.capabilities().externalMemoryFd) {
        r.note = "device lacks VK_KHR_external_memory_fd";
        return r;
    }
    std::string why;
    std::unique_ptr<GlContext> gl = GlContext::create(&why);
    if (!gl) {
        r.note = "no OpenGL 4.5 context: " + why;
        return r;
    }
    for (const char* ext : {"GL_EXT_memory_object", "GL_EXT_memory_object_fd"}) {
        if (!gl->hasExtension(ext)) {
            r.note = "OpenGL (" + gl->renderer() + ") lacks " + ext;
            return r;
        }
    }
    if (!sameUuids(ctx, *gl)) {
        r.note = "the OpenGL context (" + gl->renderer() + ") is not on this Vulkan device (device/driver UUIDs differ)";
        return r;
    }
    try {
        const std::string error = roundTrip(ctx, *gl, 4, 4);
        if (!error.empty()) {
            r.note = "the 4x4 image round trip failed: " + error;
            return r;
        }
    } catch (const vk::DeviceLostError&) {
        throw;  // the device is gone: the caller reports that, not a missing rung
    } catch (const vk::OutOfDeviceMemoryError&) {
        throw;
    } catch (const std::exception& e) {
        r.note = std::string("the 4x4 image round trip failed: ") + e.what();
        return r;
    }
    r.atomicFloat = gl->hasExtension("GL_NV_shader_atomic_float");
    r.atomicFp16Vector = gl->hasExtension("GL_NV_shader_atomic_fp16_vector");
    r.semaphoreFd = gl->hasExtension("GL_EXT_semaphore_fd");
    // Every GL pass hands off in this mode (gl_sync.hpp); IDK_GL_SYNC=cpu forces the CPU-side waits.
    gl->setSync(chooseSyncMode(querySyncCapabilities(ctx, *gl), std::getenv("IDK_GL_SYNC")));
    if (gl->sync().mode == SyncMode::Semaphores) {
        // The extensions are listed; the import itself must work too, or every GL pass would fail on it.
        try {
            HandOff check(ctx, *gl, "probe hand-off");
        } catch (const vk::DeviceLostError&) {
            throw;
        } catch (const vk::OutOfDeviceMemoryError&) {
            throw;
        } catch (const std::exception& e) {
            gl->setSync({SyncMode::CpuWait, std::string("exporting semaphores to GL failed: ") + e.what()});
        }
    }
    r.note = "OpenGL " + gl->version() + " on " + gl->renderer() + " (EGL " + gl->platform() + "); sync: " +
             syncText(gl->sync());
    r.context = std::move(gl);
    return r;
}

}  // namespace idk::gl
