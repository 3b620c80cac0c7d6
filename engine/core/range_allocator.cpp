// range_allocator.cpp: best-fit offset allocation over [0, capacity) with two indices of the free ranges
// (by offset for coalescing, by size for best fit) and a map of live blocks. See range_allocator.hpp.
#include "core/range_allocator.hpp"

#include <algorithm>
#include <iterator>
#include <stdexcept>
#include <vector>

namespace idk::core {

namespace {

bool isPowerOfTwo(uint64_t v) { return v != 0 && (v & (v - 1)) == 0; }

}  // namespace

RangeAllocator::RangeAllocator(uint64_t capacity) : capacity_(capacity) {
    if (capacity == 0) {
        throw std::invalid_argument("RangeAllocator: capacity must be greater than zero");
    }
    insertFree(0, capacity);
}

void RangeAllocator::insertFree(uint64_t offset, uint64_t size) {
    freeByOffset_.emplace(offset, size);
    freeBySize_.emplace(size, offset);
}

void RangeAllocator::eraseFree(std::map<uint64_t, uint64_t>::iterator it) {
    freeBySize_.erase({it->second, it->first});
    freeByOffset_.erase(it);
}

std::optional<uint64_t> RangeAllocator::allocate(uint64_t size, uint64_t alignment) {
    if (size == 0) {
        throw std::invalid_argument("RangeAllocator::allocate: size must be greater than zero");
    }
    if (!isPowerOfTwo(alignment)) {
        throw std::invalid_argument("RangeAllocator::allocate: alignment " + std::to_string(alignment) +
                                    " is not a power of two");
    }
    // Smallest range first; a range fits when its aligned start still leaves `size` bytes. Ties go to the
    // lowest offset because the set orders (size, offset) pairs.
    for (auto it = freeBySize_.lower_bound({size, 0}); it != freeBySize_.end(); ++it) {
        const uint64_t rangeSize = it->first;
        const uint64_t rangeOffset = it->second;
        const uint64_t padding = (alignment - (rangeOffset & (alignment - 1))) & (alignment - 1);
        if (padding > rangeSize || rangeSize - padding < size) {
            continue;
        }
        const uint64_t offset = rangeOffset + padding;
        const uint64_t tail = rangeSize - padding - size;
        eraseFree(freeByOffset_.find(rangeOffset));
        if (padding > 0) {
            insertFree(rangeOffset, padding);
        }
        if (tail > 0) {
            insertFree(offset + size, tail);
        }
        allocations_.emplace(offset, size);
        used_ += size;
        return offset;
    }
    return std::nullopt;
}

void RangeAllocator::free(uint64_t offset) {
    const auto alloc = allocations_.find(offset);
    if (alloc == allocations_.end()) {
        throw std::logic_error("RangeAllocator::free: no allocation starts at offset " + std::to_string(offset));
    }
    uint64_t start = offset;
    uint64_t size = alloc->second;
    const uint64_t end = offset + size;
    used_ -= size;
    allocations_.erase(alloc);

    // Merge with the free range that ends at `offset` and with the one that begins at `end`.
    auto next = freeByOffset_.lower_bound(offset);
    if (next != freeByOffset_.end() && next->first == end) {
        size += next->second;
        auto after = std::next(next);
        eraseFree(next);
        next = after;
    }
    if (next != freeByOffset_.begin()) {
        auto prev = std::prev(next);
        if (prev->first + prev->second == offset) {
            start = prev->first;
            size += prev->second;
            eraseFree(prev);
        }
    }
    insertFree(start, size);
}

std::optional<uint64_t> RangeAllocator::allocationSize(uint64_t offset) const {
    const auto it = allocations_.find(offset);
    if (it == allocations_.end()) {
        return std::nullopt;
    }
    return it->second;
}

uint64_t RangeAllocator::largestFreeRange() const noexcept {
    return freeBySize_.empty() ? 0 : freeBySize_.rbegin()->first;
}

bool RangeAllocator::checkInvariants(std::string* why) const {
    auto fail = [why](std::string message) {
        if (why != nullptr) {
            *why = std::move(message);
        }
        return false;
    };
    if (freeByOffset_.size() != freeBySize_.size()) {
        return fail("free indices differ in size: " + std::to_string(freeByOffset_.size()) + " by offset, " +
                    std::to_string(freeBySize_.size()) + " by size");
    }
    struct Piece {
        uint64_t offset, size;
        bool isFree;
    };
    std::vector<Piece> pieces;
    pieces.reserve(freeByOffset_.size() + allocations_.size());
    for (const auto& [offset, size] : freeByOffset_) {
        if (size == 0) {
            return fail("empty free range at " + std::to_string(offset));
        }
        if (!freeBySize_.contains({size, offset})) {
            return fail("free range at " + std::to_string(offset) + " missing from the size index");
        }
        pieces.push_back({offset, size, true});
    }
    uint64_t usedSum = 0;
    for (const auto& [offset, size] : allocations_) {
        if (size == 0) {
            return fail("empty allocation at " + std::to_string(offset));
        }
        usedSum += size;
        pieces.push_back({offset, size, false});
    }
    if (usedSum != used_) {
        return fail("used() is " + std::to_string(used_) + " but allocations sum to " + std::to_string(usedSum));
    }
    std::sort(pieces.begin(), pieces.end(), [](const Piece& a, const Piece& b) { return a.offset < b.offset; });
    uint64_t cursor = 0;
    bool previousFree = false;
    for (const Piece& p : pieces) {
        if (p.offset != cursor) {
            return fail((p.offset < cursor ? "overlap at " : "gap before ") + std::to_string(p.offset));
        }
        if (p.size > capacity_ - p.offset) {
            return fail("range at " + std::to_string(p.offset) + " runs past the capacity");
        }
        if (p.isFree && previousFree) {
            return fail("adjacent free ranges not coalesced at " + std::to_string(p.offset));
        }
        previousFree = p.isFree;
        cursor = p.offset + p.size;
    }
    if (cursor != capacity_) {
        return fail("ranges end at " + std::to_string(cursor) + ", capacity is " + std::to_string(capacity_));
    }
    return true;
}

}  // namespace idk::core
