#version 460
// debug_voxels.comp.glsl: the voxel debug view (--gi-debug voxels). Per output pixel, the camera ray through the
// pixel centre walks the cells of one level (Amanatides & Woo 1987: step to whichever cell face the ray crosses
// next) and the first cell whose coverage exceeds kVxgiDebugCoverage gives the pixel its radiance (rgb) and, in
// alpha, the distance from the camera to the middle of the ray's stretch inside that cell (> 0: it names the cell,
// so a test can tell which cell was hit); rays that hit nothing are black with alpha 0. Level 0 is the grid itself
// (radiance and coverage as the voxelization merged them, the same in every direction); level L >= 1 reads the directional volumes' level L facing the ray, the
// three axis volumes weighted by |dir| exactly as the cone tracer combines them (shared/vxgi_cone.h). Cells are
// read with imageLoad: no filtering, so each pixel shows one cell. On a real GPU neighbouring rays walk different
// cell counts (divergence; lavapipe hides it); a debug view accepts that. Ports the role of IDKEngine's
// VXGI/Voxelize/DebugVisualization/compute.glsl.
#extension GL_GOOGLE_include_directive : require
#include "scene_buffers.glsl"
#include "voxel_images.glsl"
#include "vxgi_cone.h"
#include "vxgi_debug_types.h"
#include "vxgi_types.h"

layout(local_size_x = kConeGroupSize, local_size_y = kConeGroupSize) in;
layout(push_constant, scalar) uniform Push { VxgiDebugPush p; };

vec4 cellValue(ivec3 cell, vec3 dir) {
    if (p.level == 0u) return imageLoad(gVoxelsRgba16f[p.volumes[0]], cell);
    uint kx = vxgiDirectionIndex(dir, 0u), ky = vxgiDirectionIndex(dir, 1u), kz = vxgiDirectionIndex(dir, 2u);
    vec4 sx = loadDirectionVoxel(p.volumes[kx], p.opacity[kx], cell);
    vec4 sy = loadDirectionVoxel(p.volumes[ky], p.opacity[ky], cell);
    vec4 sz = loadDirectionVoxel(p.volumes[kz], p.opacity[kz], cell);
    return vxgiCombine(dir, sx, sy, sz);
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(gImagesRgba16f[p.target]);
    if (any(greaterThanEqual(pixel, size))) return;
    GpuFrame f = FrameBuffer(p.frame).frame;
    // The ray through the pixel centre: from the camera to the point at NDC depth 0.5 (any depth lies on it).
    vec2 ndc = (vec2(pixel) + 0.5) / vec2(size) * 2.0 - 1.0;
    vec4 h = f.inverseViewProjection * vec4(ndc, 0.5, 1.0);
    vec3 origin = f.cameraPosition;
    vec3 dir = normalize(h.xyz / h.w - origin);
    // No zero components: 1/0 would give inf * 0 = NaN below when the origin lies on a cell face.
    dir = mix(dir, vec3(1e-8), lessThan(abs(dir), vec3(1e-8)));

    uint n = max(p.gridSize >> p.level, 1u);
    float cellSize = p.voxelSize * float(p.gridSize) / float(n);
    // In cell units: the grid is [0, n]^3. Clip the ray to it (slab test), then walk from the entry point.
    vec3 o = (origin - p.gridMin) / cellSize;
    vec3 inv = 1.0 / dir;
    vec3 t0 = (vec3(0.0) - o) * inv, t1 = (vec3(float(n)) - o) * inv;
    float tEnter = max(max(max(min(t0.x, t1.x), min(t0.y, t1.y)), min(t0.z, t1.z)), 0.0);
    float tExit = min(min(max(t0.x, t1.x), max(t0.y, t1.y)), max(t0.z, t1.z));
    vec4 result = vec4(0.0);
    if (tEnter < tExit) {
        ivec3 cell = clamp(ivec3(floor(o + dir * tEnter)), ivec3(0), ivec3(n - 1u));
        ivec3 stepDir = ivec3(sign(dir));
        vec3 next = vec3(cell) + max(vec3(stepDir), vec3(0.0));  // the face the ray leaves each axis through
        vec3 tMax = (next - o) * inv;
        vec3 tDelta = abs(inv);
        float tCell = tEnter;  // where the ray entered the current cell
        for (uint i = 0u; i < 3u * n; ++i) {
            float tLeave = min(min(tMax.x, tMax.y), tMax.z);
            vec4 v = cellValue(cell, dir);
            // A cell the ray only touches (an empty stretch: the camera on a cell face, a ray through an edge) is
            // not entered: skip it.
            if (tLeave > tCell && v.a > kVxgiDebugCoverage) {
                result = vec4(v.rgb, 0.5 * (tCell + tLeave) * cellSize);
                break;
            }
            tCell = tLeave;
            if (tMax.x < tMax.y && tMax.x < tMax.z) {
                cell.x += stepDir.x;
                tMax.x += tDelta.x;
            } else if (tMax.y < tMax.z) {
                cell.y += stepDir.y;
                tMax.y += tDelta.y;
            } else {
                cell.z += stepDir.z;
                tMax.z += tDelta.z;
            }
            if (any(lessThan(cell, ivec3(0))) || any(greaterThanEqual(cell, ivec3(n)))) break;
        }
    }
    imageStore(gImagesRgba16f[p.target], pixel, result);
}
