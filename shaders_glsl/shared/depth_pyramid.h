// depth_pyramid.h: the Hi-Z depth pyramid (culling/hiz_build.comp.glsl builds it, render/depth_pyramid.cpp is its
// CPU reference) and the occlusion test that reads it, one source for C++ and GLSL.
//
// Convention (FrameContext::depthPyramid): a float buffer holding levels 0..levelCount-1 one after the other, each
// row-major. Depth is the G-buffer's: 0 near .. 1 far, NOT reversed, background 1. Each texel holds the MAXIMUM
// (farthest) depth of the pixels it covers. Level k has ceil(w / 2^(k+1)) x ceil(h / 2^(k+1)) texels for a w x h
// depth image (level 0 is already half size), and texel (x, y) of level k covers exactly the depth pixels
// [x 2^(k+1), (x+1) 2^(k+1)) x [y 2^(k+1), (y+1) 2^(k+1)) clipped to the image: any size works, odd and
// non-power-of-two included (an edge texel simply covers fewer pixels; nothing is resampled).
// The last level is 1 x 1. Ports the role of IDKEngine's Hi-Z mips (MeshCulling/Camera/HiZGenerate), which keep a
// full-size mip 0 and fold 3x3 at odd edges.
#ifndef IDK_DEPTH_PYRAMID_H
#define IDK_DEPTH_PYRAMID_H
#include "interop.h"

IDK_GPU_BEGIN

IDK_CONST(uint, kHizGroupSize, 8);     // hiz_level.glsl (the SSR pyramid): 8 x 8 texels per workgroup
IDK_CONST(uint, kHizTile, 32);         // culling/hiz_build.comp: 32 x 32 texels of its first level per workgroup
IDK_CONST(uint, kHizTileLevels, 6);    // the levels one hiz_build dispatch reduces a tile to (32 x 32 .. 1 x 1)
IDK_CONST(uint, kHizMaxLevels, 16);    // enough for 65536-pixel sides

struct HizBuildPush {
    DeviceAddress pyramid;  // float[]: the whole pyramid
    uvec2 depthSize;        // w, h of the depth image
    uint depth;             // bindless storage index of the R32F depth image (read by level 0)
    uint level;             // the level this dispatch writes (reads level - 1, or the image for 0); hiz_build:
                            // bits 16+ = how many levels from there (<= kHizTileLevels; 0 means 1)
};
IDK_GPU_SIZE(HizBuildPush, 24);

// culling/hiz_reduce.comp (the sampler rung of the ladder "hiz-reduction", passes/depth_pyramid_minmax.cpp copies
// each level into an image for the next): one bilinear sample with a MAX
// reduction sampler at the shared corner of each 2 x 2 block returns the block's maximum (clamp-to-edge folds the
// missing column/row at odd edges onto the last one, as the compute rung's clipped 2 x 2 does).
struct HizReducePush {
    DeviceAddress pyramid;  // float[]: the whole pyramid (the culling passes read this)
    uvec2 depthSize;        // w, h of the depth image
    uint source;            // bindless sampled index: the depth image (level 0) or level - 1's image
    uint samplerIndex;      // bindless sampler index: linear, clamp to edge, reduction MAX
    uint level;
    uint pad0;
};
IDK_GPU_SIZE(HizReducePush, 32);

IDK_INLINE uvec2 hizLevelSize(uvec2 depthSize, uint level) {
    uint shift = level + 1u;
    return (depthSize + uvec2((1u << shift) - 1u)) >> shift;
}

// Levels down to 1 x 1 (at least one).
IDK_INLINE uint hizLevelCount(uvec2 depthSize) {
    uint levels = 1u;
    while (levels < kHizMaxLevels && (hizLevelSize(depthSize, levels - 1u).x > 1u ||
                                      hizLevelSize(depthSize, levels - 1u).y > 1u))
        ++levels;
    return levels;
}

// First float of `level` in the pyramid buffer; hizLevelOffset(size, hizLevelCount(size)) is the total count.
IDK_INLINE uint hizLevelOffset(uvec2 depthSize, uint level) {
    uint offset = 0u;
    for (uint k = 0u; k < level; ++k) {
        uvec2 s = hizLevelSize(depthSize, k);
        offset += s.x * s.y;
    }
    return offset;
}

// The screen footprint of a world box seen through `viewProjection` on a viewport of `viewport` pixels: `rect` =
// (min x, min y, max x, max y) in pixels of the eight projected corners, `nearestDepth` their smallest depth (the
// nearest point of a box is a corner: depth grows with view distance, which is linear over the box). False when a
// corner is behind the eye or in front of the near plane (w <= 0 or z < 0): the projection is unbounded there, and
// the caller must treat the box as visible. Conservative: every fragment of geometry inside the box has its
// pixel centre inside `rect` and a depth >= nearestDepth.
IDK_INLINE bool hizFootprint(mat4 viewProjection, vec3 center, vec3 extent, vec2 viewport, IDK_OUT(vec4) rect,
                             IDK_OUT(float) nearestDepth) {
    rect = vec4(1e30f, 1e30f, -1e30f, -1e30f);
    nearestDepth = 1e30f;
    for (int c = 0; c < 8; ++c) {
        vec3 s = vec3((c & 1) != 0 ? 1.0f : -1.0f, (c & 2) != 0 ? 1.0f : -1.0f, (c & 4) != 0 ? 1.0f : -1.0f);
        vec4 clip = viewProjection * vec4(center + s * extent, 1.0f);
        if (clip.w <= 0.0f || clip.z < 0.0f) return false;
        vec3 ndc = vec3(clip) / clip.w;
        vec2 pixel = (vec2(ndc) * 0.5f + 0.5f) * viewport;
        rect = vec4(min(vec2(rect), pixel), max(vec2(rect.z, rect.w), pixel));
        nearestDepth = ndc.z < nearestDepth ? ndc.z : nearestDepth;  // (no scalar min in C++ by ADL)
    }
    return true;
}

// The level and the texels (x0, y0, x1, y1), at most 2 x 2, that cover the pixels of `rect` (clamped to the
// viewport): the finest level where the covered pixel range spans at most two texels per axis.
IDK_INLINE uint hizTexels(vec4 rect, uvec2 depthSize, IDK_OUT(uvec4) texels) {
    vec2 hi = vec2(depthSize) - 1.0f;
    uvec2 p0 = uvec2(clamp(vec2(rect), vec2(0.0f), hi));
    uvec2 p1 = uvec2(clamp(vec2(rect.z, rect.w), vec2(0.0f), hi));
    uint levels = hizLevelCount(depthSize);
    uint level = 0u;
    while (level + 1u < levels && ((p1.x >> (level + 1u)) - (p0.x >> (level + 1u)) > 1u ||
                                   (p1.y >> (level + 1u)) - (p0.y >> (level + 1u)) > 1u))
        ++level;
    texels = uvec4(p0 >> (level + 1u), p1 >> (level + 1u));
    return level;
}

IDK_GPU_END
#endif
