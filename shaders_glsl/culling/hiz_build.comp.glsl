#version 460
// hiz_build.comp.glsl: levels first .. first + count - 1 (count <= kHizTileLevels) of the Hi-Z depth pyramid
// (shared/depth_pyramid.h) in one dispatch: each workgroup reduces one tile of kHizTile x kHizTile texels of level
// `first` (each texel the maximum of the 2 x 2 texels below it: the depth image's pixels for level 0, fewer at
// odd edges, none resampled), keeps the tile in shared memory and reduces it level by level to one texel. Texels
// past a level's edge hold -infinity, so an edge texel is the maximum of the texels it really covers, exactly as
// the CPU reduction (render::buildDepthPyramid). passes/depth_pyramid.cpp dispatches it again for the levels left
// (count = 1: the one-dispatch-per-level build). The portable compute rung (no sampler reduction mode needed).
// On a real GPU this saves nine of eleven dispatches and their barriers at 1280x720 (a subgroupMax over 2 x 2
// quads, and every level in one dispatch with a last-workgroup atomic as AMD's single-pass downsampler does, would
// save more); lavapipe runs workgroup barriers slowly: there it takes 14.8 ms against 6.8 ms for one dispatch per
// level (BM_HizBuild), and the culling there uses the sampler rung anyway.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#include "bindless.glsl"
#include "depth_pyramid.h"

layout(local_size_x = kHizTile / 2u, local_size_y = kHizTile / 2u) in;
layout(push_constant, scalar) uniform Push { HizBuildPush p; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Pyramid { float data[]; };

shared float tile[kHizTile * kHizTile];  // the current level's texels of this workgroup's tile, row stride kHizTile

float none() { return uintBitsToFloat(0xff800000u); }  // -infinity: max(x, none()) == x

// Texel t of the level below `first` (the depth image for level 0), none() past its edge.
float below(uvec2 t, uint first, uvec2 belowSize, uint belowOffset) {
    if (any(greaterThanEqual(t, belowSize))) return none();
    if (first == 0u) return imageLoad(gImagesR32f[p.depth], ivec2(t)).r;
    return Pyramid(p.pyramid).data[belowOffset + t.y * belowSize.x + t.x];
}

void main() {
    uint first = p.level & 0xFFFFu;
    uint count = max(p.level >> 16, 1u);
    uvec2 belowSize = first == 0u ? p.depthSize : hizLevelSize(p.depthSize, first - 1u);
    uint belowOffset = first == 0u ? 0u : hizLevelOffset(p.depthSize, first - 1u);
    uvec2 origin = gl_WorkGroupID.xy * kHizTile;
    uvec2 size = hizLevelSize(p.depthSize, first);
    uint offset = hizLevelOffset(p.depthSize, first);
    // Level `first`: 2 x 2 texels per invocation.
    for (uint k = 0u; k < 4u; ++k) {
        uvec2 l = gl_LocalInvocationID.xy * 2u + uvec2(k & 1u, k >> 1u);
        uvec2 t = origin + l;
        float d = none();
        if (all(lessThan(t, size))) {
            uvec2 a = t * 2u;
            d = max(max(below(a, first, belowSize, belowOffset), below(a + uvec2(1, 0), first, belowSize, belowOffset)),
                    max(below(a + uvec2(0, 1), first, belowSize, belowOffset),
                        below(a + uvec2(1, 1), first, belowSize, belowOffset)));
            Pyramid(p.pyramid).data[offset + t.y * size.x + t.x] = d;
        }
        tile[l.y * kHizTile + l.x] = d;
    }
    barrier();
    // The next levels from shared memory: texel l of level first + k covers texels 2l .. 2l + 1 of the one before.
    for (uint k = 1u; k < count; ++k) {
        uint n = kHizTile >> k;
        uint i = gl_LocalInvocationIndex;
        uvec2 l = uvec2(i % n, i / n);
        bool inTile = i < n * n;
        float d = none();
        if (inTile) {
            uint s = 2u * l.y * kHizTile + 2u * l.x;
            d = max(max(tile[s], tile[s + 1u]), max(tile[s + kHizTile], tile[s + kHizTile + 1u]));
        }
        barrier();  // every read of the level before, before any write over it
        if (inTile) {
            tile[l.y * kHizTile + l.x] = d;
            size = hizLevelSize(p.depthSize, first + k);
            uvec2 t = (origin >> k) + l;
            if (all(lessThan(t, size)))
                Pyramid(p.pyramid).data[hizLevelOffset(p.depthSize, first + k) + t.y * size.x + t.x] = d;
        }
        barrier();
    }
}
