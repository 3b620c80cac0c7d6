// radix_sort.cpp: three stable counting-sort passes over 11-bit digits (a pass whose digit is the same for every
// key is skipped).
#include "bvh/radix_sort.hpp"

#include <algorithm>
#include <array>
#include <numeric>
#include <vector>

namespace idk::bvh {

void radixSortIndices(std::span<const uint32_t> keys, std::span<uint32_t> order) {
    constexpr uint32_t kDigitBits = 11;
    constexpr uint32_t kDigits = 1u << kDigitBits;
    const size_t n = keys.size();
    std::vector<uint32_t> keyA(keys.begin(), keys.end()), keyB(n);
    std::vector<uint32_t> idxA(n), idxB(n);
    std::iota(idxA.begin(), idxA.end(), 0u);
    std::array<uint32_t, kDigits> offsets{};
    for (uint32_t shift = 0; shift < 32; shift += kDigitBits) {
        offsets.fill(0);
        for (size_t i = 0; i < n; ++i) ++offsets[(keyA[i] >> shift) & (kDigits - 1)];
        if (n == 0 || offsets[(keyA[0] >> shift) & (kDigits - 1)] == n) continue;  // one digit: nothing moves
        uint32_t sum = 0;
        for (uint32_t& o : offsets) {
            const uint32_t c = o;
            o = sum;
            sum += c;
        }
        for (size_t i = 0; i < n; ++i) {
            const uint32_t dst = offsets[(keyA[i] >> shift) & (kDigits - 1)]++;
            keyB[dst] = keyA[i];
            idxB[dst] = idxA[i];
        }
        keyA.swap(keyB);
        idxA.swap(idxB);
    }
    std::copy(idxA.begin(), idxA.end(), order.begin());
}

}  // namespace idk::bvh
