// fake_backend.hpp: a GPU-free GraphBackend for the render-graph tests, plus fake vkCmd* entry points
// installed into volk's global function pointers so execute() can be recorded and inspected without a device.
#pragma once
#include "graph/render_graph.hpp"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace idk::graph::testing {

// Everything the fake backend and the fake vkCmd* functions saw, in order ("beginFrame 3", "label gbuffer",
// "timestampBegin 0 gbuffer", "barrier m1 i2", "exec gbuffer", "clearColor", ...).
inline std::vector<std::string>& eventLog() {
    static std::vector<std::string> log;
    return log;
}

struct RecordedDependency {
    std::vector<VkMemoryBarrier2> memory;
    std::vector<VkImageMemoryBarrier2> images;
};
inline std::vector<RecordedDependency>& recordedDependencies() {
    static std::vector<RecordedDependency> deps;
    return deps;
}
inline std::vector<VkImage>& clearedImages() {
    static std::vector<VkImage> images;
    return images;
}

inline void VKAPI_CALL fakePipelineBarrier2(VkCommandBuffer, const VkDependencyInfo* info) {
    RecordedDependency dep;
    dep.memory.assign(info->pMemoryBarriers, info->pMemoryBarriers + info->memoryBarrierCount);
    dep.images.assign(info->pImageMemoryBarriers, info->pImageMemoryBarriers + info->imageMemoryBarrierCount);
    eventLog().push_back("barrier m" + std::to_string(dep.memory.size()) + " i" + std::to_string(dep.images.size()));
    recordedDependencies().push_back(std::move(dep));
}
inline void VKAPI_CALL fakeBeginLabel(VkCommandBuffer, const VkDebugUtilsLabelEXT* label) {
    eventLog().push_back(std::string("label ") + label->pLabelName);
}
inline void VKAPI_CALL fakeEndLabel(VkCommandBuffer) { eventLog().push_back("endLabel"); }
inline void VKAPI_CALL fakeClearColor(VkCommandBuffer, VkImage image, VkImageLayout layout, const VkClearColorValue*,
                                      uint32_t, const VkImageSubresourceRange*) {
    eventLog().push_back(layout == VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL ? "clearColor" : "clearColor(bad layout)");
    clearedImages().push_back(image);
}
inline void VKAPI_CALL fakeClearDepth(VkCommandBuffer, VkImage image, VkImageLayout, const VkClearDepthStencilValue*,
                                      uint32_t, const VkImageSubresourceRange*) {
    eventLog().push_back("clearDepth");
    clearedImages().push_back(image);
}
inline void VKAPI_CALL fakeFillBuffer(VkCommandBuffer, VkBuffer, VkDeviceSize, VkDeviceSize, uint32_t) {
    eventLog().push_back("fillBuffer");
}

// Installs the fakes for the lifetime of the object (and clears the logs).
struct FakeVulkanCommands {
    FakeVulkanCommands() {
        eventLog().clear();
        recordedDependencies().clear();
        clearedImages().clear();
        vkCmdPipelineBarrier2 = fakePipelineBarrier2;
        vkCmdBeginDebugUtilsLabelEXT = fakeBeginLabel;
        vkCmdEndDebugUtilsLabelEXT = fakeEndLabel;
        vkCmdClearColorImage = fakeClearColor;
        vkCmdClearDepthStencilImage = fakeClearDepth;
        vkCmdFillBuffer = fakeFillBuffer;
    }
    ~FakeVulkanCommands() {
        vkCmdPipelineBarrier2 = nullptr;
        vkCmdBeginDebugUtilsLabelEXT = nullptr;
        vkCmdEndDebugUtilsLabelEXT = nullptr;
        vkCmdClearColorImage = nullptr;
        vkCmdClearDepthStencilImage = nullptr;
        vkCmdFillBuffer = nullptr;
    }
};

template <class Handle>
Handle fakeHandle(uint64_t value) {
    return reinterpret_cast<Handle>(static_cast<uintptr_t>(value));
}

class FakeBackend : public GraphBackend {
public:
    // Overridable requirement functions (default: 4 bytes per texel per layer, mips double it, 256-byte
    // alignment, memory type bit 0; buffers: size rounded up to 16, 16-byte alignment).
    std::function<MemoryRequirements(const TextureInfo&)> textureRule = [](const TextureInfo& t) {
        VkDeviceSize size = VkDeviceSize{t.extent.width} * t.extent.height * t.extent.depth * t.layers * 4;
        if (t.mips > 1) size *= 2;
        return MemoryRequirements{(size + 255) / 256 * 256, 256, 0b1};
    };
    std::function<MemoryRequirements(const BufferInfo&)> bufferRule = [](const BufferInfo& b) {
        return MemoryRequirements{(b.size + 15) / 16 * 16, 16, b.hostVisible ? 0b10u : 0b1u};
    };

    struct Created {
        std::string name;
        bool placed = false;
        MemoryPlacement placement;
        TextureInfo texture;
        BufferInfo buffer;
    };
    std::vector<Created> createdTextures, createdBuffers;
    std::vector<HeapDesc> allocatedHeaps;
    std::vector<HeapHandle> releasedHeaps;
    std::vector<VkImage> destroyedImages;
    std::vector<VkBuffer> destroyedBuffers;
    uint32_t requirementQueries = 0;

    MemoryRequirements textureRequirements(const TextureInfo& info) override {
        ++requirementQueries;
        return textureRule(info);
    }
    MemoryRequirements bufferRequirements(const BufferInfo& info) override {
        ++requirementQueries;
        return bufferRule(info);
    }
    HeapHandle allocateHeap(const HeapDesc& desc) override {
        allocatedHeaps.push_back(desc);
        return HeapHandle{0x100 + allocatedHeaps.size()};
    }
    PhysicalTexture createTexture(const TextureInfo& info, std::string_view name, const MemoryPlacement* placement) override {
        createdTextures.push_back(Created{std::string(name), placement != nullptr, placement ? *placement : MemoryPlacement{}, info, {}});
        PhysicalTexture t;
        t.image = fakeHandle<VkImage>(0x1000 + createdTextures.size());
        t.view = fakeHandle<VkImageView>(0x2000 + createdTextures.size());
        t.format = info.format;
        t.extent = info.extent;
        t.mips = info.mips;
        t.layers = info.layers;
        t.sampledIndex = static_cast<uint32_t>(createdTextures.size());
        return t;
    }
    PhysicalBuffer createBuffer(const BufferInfo& info, std::string_view name, const MemoryPlacement* placement) override {
        createdBuffers.push_back(Created{std::string(name), placement != nullptr, placement ? *placement : MemoryPlacement{}, {}, info});
        PhysicalBuffer b;
        b.buffer = fakeHandle<VkBuffer>(0x3000 + createdBuffers.size());
        b.size = info.size;
        b.storageIndex = static_cast<uint32_t>(createdBuffers.size());
        return b;
    }
    void destroyTexture(const PhysicalTexture& t) override { destroyedImages.push_back(t.image); }
    void destroyBuffer(const PhysicalBuffer& b) override { destroyedBuffers.push_back(b.buffer); }
    void releaseHeap(HeapHandle heap) override { releasedHeaps.push_back(heap); }

    void beginFrame(VkCommandBuffer, uint32_t passCount) override {
        eventLog().push_back("beginFrame " + std::to_string(passCount));
    }
    void timestampBegin(VkCommandBuffer, uint32_t passIndex, std::string_view name) override {
        eventLog().push_back("timestampBegin " + std::to_string(passIndex) + " " + std::string(name));
    }
    void timestampEnd(VkCommandBuffer, uint32_t passIndex) override {
        eventLog().push_back("timestampEnd " + std::to_string(passIndex));
    }
};

inline TextureDesc colorDesc(VkFormat format = VK_FORMAT_R8G8B8A8_UNORM) {
    TextureDesc d;
    d.format = format;
    return d;
}

inline TextureDesc absoluteDesc(uint32_t width, uint32_t height, VkFormat format = VK_FORMAT_R8G8B8A8_UNORM) {
    TextureDesc d;
    d.format = format;
    d.sizeMode = SizeMode::Absolute;
    d.extent = {width, height, 1};
    return d;
}

inline VkCommandBuffer fakeCmd() { return fakeHandle<VkCommandBuffer>(0xC0DE); }

}  // namespace idk::graph::testing
