// voxelize_key.glsl: the voxels' depth keys of the front-most rule (shared/vxgi_depth_key.h): an R32UI image of
// N x N x 2D texels for a slab of D voxels in z (passes/vxgi_passes.hpp voxelDepthKeyExtent), texel (x, y, 2 z + s)
// holding the slab's voxel (x, y, z)'s keys of facing sign s (0: +, 1: -), one 10-bit field per axis. The key pass raises a field to a fragment's key; the accumulating passes read it back.
#ifndef IDK_VOXELIZE_KEY_GLSL
#define IDK_VOXELIZE_KEY_GLSL
#include "vxgi_depth_key.h"
#include "voxel_images.glsl"

ivec3 voxelKeyTexel(ivec3 voxel, uint facingClass) {
    return ivec3(voxel.x, voxel.y, 2 * voxel.z + int(facingClass & 1u));
}

uint voxelKeyShift(uint facingClass) { return kVoxelKeyBits * (facingClass >> 1u); }

// Raises the class's field of the voxel's key word to at least `key`. Three classes share a word and image atomics
// have no per-field max, so a compare-and-swap loop: each failed swap means another fragment raised some field of
// the word, which happens a bounded number of times (keys only grow), so the loop is lock-free; on a GPU the
// contended words are the few voxels where surfaces meet. The bound only guards against a pathological pile-up: a
// key left low can keep a hidden fragment, never drop a front one.
void raiseVoxelKey(uint image, ivec3 voxel, uint facingClass, uint key) {
    ivec3 texel = voxelKeyTexel(voxel, facingClass);
    uint shift = voxelKeyShift(facingClass);
    uint mask = kVoxelKeyMax << shift;
    uint seen = 0u;  // the clear's value: the first swap succeeds in an untouched word
    for (uint attempt = 0u; attempt < 256u; ++attempt) {
        if (((seen & mask) >> shift) >= key) return;
        uint prev = imageAtomicCompSwap(gVoxelsR32ui[image], texel, seen, (seen & ~mask) | (key << shift));
        if (prev == seen) return;
        seen = prev;
    }
}

// Whether a fragment of this class and key is among the voxel's front-most (within kVoxelKeyTolerance).
bool voxelFrontMost(uint image, ivec3 voxel, uint facingClass, uint key) {
    uint word = imageLoad(gVoxelsR32ui[image], voxelKeyTexel(voxel, facingClass)).r;
    return key + kVoxelKeyTolerance >= ((word >> voxelKeyShift(facingClass)) & kVoxelKeyMax);
}

#endif
