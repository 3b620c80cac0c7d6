// radix_sort.hpp: LSB radix sort of 32-bit keys carrying a 32-bit index (3 passes of 11 bits, stable), used once
// per axis before the BVH recursion, plus the float -> order-preserving uint key transform.
#pragma once

#include <bit>
#include <cstdint>
#include <span>

namespace idk::bvh {

// Maps a float to an unsigned key with the same order (negative floats reversed, sign bit flipped). -0 sorts
// just below +0. NaN must not be passed (the builder filters non-finite input).
inline uint32_t sortableFloatKey(float f) {
    const uint32_t bits = std::bit_cast<uint32_t>(f);
    return bits ^ ((bits >> 31) != 0 ? 0xFFFFFFFFu : 0x80000000u);
}

// Writes to `order` the indices 0..n-1 sorted by keys[i]; equal keys keep increasing index order.
// `order.size()` must equal `keys.size()`.
void radixSortIndices(std::span<const uint32_t> keys, std::span<uint32_t> order);

}  // namespace idk::bvh
