// indirect_draw.hpp: the one way passes record an uncounted multi-draw-indirect of indexed draws, and the layout of
// the CPU-built indirect buffers it needs (the scene's draw commands, the shadow casters' and the sorted BLEND draws):
// the commands, then ONE count word holding 0xFFFFFFFF.
// Why: lavapipe (Mesa 25.0.7) keeps the count buffer of the last vkCmdDrawIndexedIndirectCount (and
// vkCmdDrawMeshTasksIndirectCountEXT) in its command-buffer draw state and applies it to LATER plain
// vkCmdDrawIndexedIndirect calls in the same command buffer, which then draw only min(stale count, drawCount)
// draws: after the GPU-culled point-shadow cube faces, the spot / cascade maps, the voxelization, the unculled
// G-buffer and point shadows, motion vectors and the BLEND draws lost every draw past the last face's count
// (tests/gpu/culling/counted_then_plain_draw_test.cpp). The Vulkan spec gives a plain indirect draw exactly
// drawCount draws whatever count draw came before; recording it as vkCmdDrawIndexedIndirectCount with a count word
// of 0xFFFFFFFF draws min(0xFFFFFFFF, maxDrawCount) = drawCount draws, the same on every conforming driver, and
// replaces the driver's stale count with our own. drawIndirectCount is a required feature (vk/context.cpp). The
// word lives in the command buffer itself, so it is uploaded with the commands and needs no barrier of its own.
#pragma once
#include <volk.h>

#include <cstdint>
#include <cstring>
#include <vector>

namespace idk::passes {

inline constexpr uint32_t kAllDrawsCountWord = 0xFFFFFFFFu;

// Bytes of an indirect buffer holding `drawCount` commands and the count word after them.
inline constexpr VkDeviceSize indirectBufferBytes(uint32_t drawCount) {
    return VkDeviceSize(drawCount) * sizeof(VkDrawIndexedIndirectCommand) + sizeof(uint32_t);
}

// `draws` followed by the count word: what an indirect buffer drawn by drawAllIndexedIndirect holds.
inline std::vector<uint8_t> withCountWord(const std::vector<VkDrawIndexedIndirectCommand>& draws) {
    std::vector<uint8_t> bytes(indirectBufferBytes(uint32_t(draws.size())));
    if (!draws.empty()) std::memcpy(bytes.data(), draws.data(), draws.size() * sizeof(VkDrawIndexedIndirectCommand));
    std::memcpy(bytes.data() + draws.size() * sizeof(VkDrawIndexedIndirectCommand), &kAllDrawsCountWord,
                sizeof(uint32_t));
    return bytes;
}

// All `drawCount` commands of `commands` (laid out as withCountWord makes them), i.e. what
// vkCmdDrawIndexedIndirect(cmd, commands, 0, drawCount, stride) means by the spec.
inline void drawAllIndexedIndirect(VkCommandBuffer cmd, VkBuffer commands, uint32_t drawCount) {
    constexpr uint32_t kStride = sizeof(VkDrawIndexedIndirectCommand);
    vkCmdDrawIndexedIndirectCount(cmd, commands, 0, commands, VkDeviceSize(drawCount) * kStride, drawCount, kStride);
}

}  // namespace idk::passes
