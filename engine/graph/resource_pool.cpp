// resource_pool.cpp: cross-frame cache of heaps, placed transients and persistent ping-pong copies.
#include "graph/resource_pool.hpp"
#include "graph/text_format.hpp"

#include <algorithm>

namespace idk::graph {

bool persistentCompatible(ResourceKind kind, const TextureInfo& haveTexture, const BufferInfo& haveBuffer,
                          const TextureInfo& wantTexture, const BufferInfo& wantBuffer) noexcept {
    if (kind == ResourceKind::Image) {
        TextureInfo sameUsage = wantTexture;
        sameUsage.usage = haveTexture.usage;
        return sameUsage == haveTexture && (wantTexture.usage & ~haveTexture.usage) == 0;
    }
    return wantBuffer.size == haveBuffer.size && wantBuffer.hostVisible == haveBuffer.hostVisible &&
           (wantBuffer.usage & ~haveBuffer.usage) == 0;
}

ResourcePool::ResourcePool(GraphBackend& backend) : backend_(backend) {}

ResourcePool::~ResourcePool() { releaseAll(); }

void ResourcePool::releaseAll() {
    for (PersistentEntry& entry : persistent_) destroyEntry(entry);
    persistent_.clear();
    while (!heaps_.empty()) releaseHeapAndContents(heaps_.size() - 1);
}

ResourcePool::Stats ResourcePool::stats() const noexcept {
    Stats s;
    s.heaps = static_cast<uint32_t>(heaps_.size());
    for (const HeapEntry& heap : heaps_) s.heapBytes += heap.desc.size;
    s.transientTextures = static_cast<uint32_t>(textures_.size());
    s.transientBuffers = static_cast<uint32_t>(buffers_.size());
    s.persistentResources = static_cast<uint32_t>(persistent_.size());
    return s;
}

const ResourcePool::PersistentEntry* ResourcePool::findPersistent(std::string_view name) const noexcept {
    for (const PersistentEntry& entry : persistent_) {
        if (entry.name == name) return &entry;
    }
    return nullptr;
}

ResourceState ResourcePool::heapTail(const HeapKey& key) const noexcept {
    for (const HeapEntry& heap : heaps_) {
        if (heap.key == key) return heap.tail;
    }
    return {};
}

ResourceState ResourcePool::heapTail(const HeapKey& key, VkDeviceSize size, VkDeviceSize alignment) const noexcept {
    for (const HeapEntry& heap : heaps_) {
        if (heap.key == key && heap.desc.size >= size && heap.desc.alignment >= alignment) return heap.tail;
    }
    return unknownHistoryState();
}

void ResourcePool::setHeapTail(const HeapKey& key, const ResourceState& tail) {
    for (HeapEntry& heap : heaps_) {
        if (heap.key == key) heap.tail = tail;
    }
}

HeapHandle ResourcePool::acquireHeap(const HeapKey& key, VkDeviceSize size, VkDeviceSize alignment) {
    for (size_t i = 0; i < heaps_.size(); ++i) {
        HeapEntry& heap = heaps_[i];
        if (heap.key != key) continue;
        if (heap.desc.size >= size && heap.desc.alignment >= alignment) {
            heap.lastUsedFrame = frameIndex_;
            return heap.handle;
        }
        // Too small: a bigger one replaces it (the backend defers freeing the old one past the GPU's use).
        // The new memory is fresh (this frame's plan waited on everything before it: see heapTail), and the
        // tail is kept for later frames: waiting on stale stages is merely conservative.
        const ResourceState tail = heap.tail;
        releaseHeapAndContents(i);
        HeapEntry grown;
        grown.key = key;
        grown.desc = HeapDesc{size, alignment, key.memoryTypeBits, key.hostVisible, key.kind};
        grown.handle = backend_.allocateHeap(grown.desc);
        grown.tail = tail;
        grown.lastUsedFrame = frameIndex_;
        heaps_.push_back(grown);
        return grown.handle;
    }
    HeapEntry heap;
    heap.key = key;
    heap.desc = HeapDesc{size, alignment, key.memoryTypeBits, key.hostVisible, key.kind};
    heap.handle = backend_.allocateHeap(heap.desc);
    heap.lastUsedFrame = frameIndex_;
    heaps_.push_back(heap);
    return heap.handle;
}

PhysicalTexture ResourcePool::acquireTexture(const TextureInfo& info, std::string_view name, HeapHandle heap,
                                             VkDeviceSize offset) {
    for (CachedTexture& cached : textures_) {
        if (cached.heap == heap && cached.offset == offset && cached.info == info) {
            cached.lastUsedFrame = frameIndex_;
            return cached.physical;
        }
    }
    const MemoryPlacement placement{heap, offset};
    CachedTexture cached{info, heap, offset, backend_.createTexture(info, name, &placement), frameIndex_};
    textures_.push_back(cached);
    return cached.physical;
}

PhysicalBuffer ResourcePool::acquireBuffer(const BufferInfo& info, std::string_view name, HeapHandle heap,
                                           VkDeviceSize offset) {
    for (CachedBuffer& cached : buffers_) {
        if (cached.heap == heap && cached.offset == offset && cached.info == info) {
            cached.lastUsedFrame = frameIndex_;
            return cached.physical;
        }
    }
    const MemoryPlacement placement{heap, offset};
    CachedBuffer cached{info, heap, offset, backend_.createBuffer(info, name, &placement), frameIndex_};
    buffers_.push_back(cached);
    return cached.physical;
}

ResourcePool::PersistentEntry& ResourcePool::acquirePersistent(std::string_view name, ResourceKind kind,
                                                               const TextureInfo& texture,
                                                               const BufferInfo& buffer) {
    auto it = std::find_if(persistent_.begin(), persistent_.end(),
                           [&](const PersistentEntry& e) { return e.name == name; });
    if (it != persistent_.end()) {
        if (it->kind == kind && persistentCompatible(kind, it->texture, it->buffer, texture, buffer)) {
            it->lastUsedFrame = frameIndex_;
            return *it;
        }
        destroyEntry(*it);
        persistent_.erase(it);
    }
    PersistentEntry entry;
    entry.name = std::string(name);
    entry.kind = kind;
    entry.texture = texture;
    entry.buffer = buffer;
    entry.lastUsedFrame = frameIndex_;
    for (uint32_t copy = 0; copy < 2; ++copy) {
        const std::string debugName = strformat("{}[{}]", name, copy);
        if (kind == ResourceKind::Image) {
            entry.textures[copy] = backend_.createTexture(texture, debugName, nullptr);
        } else {
            entry.buffers[copy] = backend_.createBuffer(buffer, debugName, nullptr);
        }
    }
    persistent_.push_back(std::move(entry));
    return persistent_.back();
}

void ResourcePool::destroyEntry(PersistentEntry& entry) {
    for (uint32_t copy = 0; copy < 2; ++copy) {
        if (entry.kind == ResourceKind::Image) {
            backend_.destroyTexture(entry.textures[copy]);
        } else {
            backend_.destroyBuffer(entry.buffers[copy]);
        }
    }
}

void ResourcePool::releaseHeapAndContents(size_t heapIndex) {
    const HeapHandle handle = heaps_[heapIndex].handle;
    std::erase_if(textures_, [&](const CachedTexture& t) {
        if (t.heap != handle) return false;
        backend_.destroyTexture(t.physical);
        return true;
    });
    std::erase_if(buffers_, [&](const CachedBuffer& b) {
        if (b.heap != handle) return false;
        backend_.destroyBuffer(b.physical);
        return true;
    });
    backend_.releaseHeap(handle);
    heaps_.erase(heaps_.begin() + static_cast<std::ptrdiff_t>(heapIndex));
}

void ResourcePool::endFrame() {
    const auto stale = [&](uint64_t lastUsed) { return lastUsed + kUnusedFramesBeforeRelease < frameIndex_; };
    std::erase_if(textures_, [&](const CachedTexture& t) {
        if (!stale(t.lastUsedFrame)) return false;
        backend_.destroyTexture(t.physical);
        return true;
    });
    std::erase_if(buffers_, [&](const CachedBuffer& b) {
        if (!stale(b.lastUsedFrame)) return false;
        backend_.destroyBuffer(b.physical);
        return true;
    });
    for (size_t i = heaps_.size(); i-- > 0;) {
        if (stale(heaps_[i].lastUsedFrame)) releaseHeapAndContents(i);
    }
    std::erase_if(persistent_, [&](PersistentEntry& e) {
        if (!stale(e.lastUsedFrame)) return false;
        destroyEntry(e);
        return true;
    });
    ++frameIndex_;
}

}  // namespace idk::graph
