// range_allocator.hpp: a pure offset allocator over one range [0, capacity) (no memory is touched).
// The Vulkan memory sub-allocator puts one on each VkDeviceMemory block. Best fit by size, lowest offset
// on ties; alignment padding in front of a block goes back to the free list; frees coalesce neighbours.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <unordered_map>
#include <utility>

namespace idk::core {

class RangeAllocator {
public:
    explicit RangeAllocator(uint64_t capacity);

    // Returns the offset of a block of `size` bytes aligned to `alignment` (a power of two), or nullopt when no
    // free range can hold it. Throws std::invalid_argument for size 0 or a non-power-of-two alignment.
    // Cost: O(log n) to find the smallest free range of at least `size` bytes, plus one step per larger range
    // whose alignment padding makes it too small (rare; worst case O(n) for large alignments on a fragmented
    // block).
    std::optional<uint64_t> allocate(uint64_t size, uint64_t alignment = 1);

    // Returns the block that starts at `offset` to the free list, merging it with free neighbours. O(log n).
    // Throws std::logic_error when no live allocation starts at `offset` (double free, foreign offset).
    void free(uint64_t offset);

    // Size in bytes of the live allocation at `offset`, or nullopt if there is none.
    std::optional<uint64_t> allocationSize(uint64_t offset) const;

    uint64_t capacity() const noexcept { return capacity_; }
    uint64_t used() const noexcept { return used_; }
    uint64_t freeBytes() const noexcept { return capacity_ - used_; }
    uint64_t largestFreeRange() const noexcept;
    uint64_t allocationCount() const noexcept { return allocations_.size(); }
    uint64_t freeRangeCount() const noexcept { return freeByOffset_.size(); }

    // Full consistency check (O(n log n)), for tests: free ranges and allocations tile [0, capacity) exactly,
    // free ranges are non-empty and never adjacent, both free-list indices agree, used() is the sum of sizes.
    // On failure returns false and, if `why` is set, a description of the first problem found.
    bool checkInvariants(std::string* why = nullptr) const;

private:
    void insertFree(uint64_t offset, uint64_t size);
    void eraseFree(std::map<uint64_t, uint64_t>::iterator it);

    uint64_t capacity_ = 0;
    uint64_t used_ = 0;
    std::map<uint64_t, uint64_t> freeByOffset_;             // offset -> size, sorted by offset (for coalescing)
    std::set<std::pair<uint64_t, uint64_t>> freeBySize_;    // (size, offset), sorted for best fit
    std::unordered_map<uint64_t, uint64_t> allocations_;    // offset -> size of live blocks
};

}  // namespace idk::core
