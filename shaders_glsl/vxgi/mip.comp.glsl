#version 460
// mip.comp.glsl: one level of the anisotropic mip chain (shared/vxgi_types.h, VoxelMipPush): per direction, the
// eight children composited front to back in pairs along it (premultiplied rgb and coverage), the four pairs
// averaged. Ports IDKEngine's VXGI mipmap shader (4x4x4 groups), which keeps one isotropic chain of 7-tap means
// instead: a thin emitter then fades by half per level and the cones see too little of it.
// Level 1 first reads the merge's cell mask (push `cells`): 0 means none of the cell's eight voxels is occupied this
// frame, so all eight are zero in every direction after the merge (stored zero, or skipped as zero already), whose
// composite is zero: the cell is stored zero without the 48 directional loads. Levels >= 2 read their children (1/8
// of level 1's work each). On a GPU the saving is bandwidth (4 instead of 384 bytes read per empty cell); a warp
// straddling a surface runs both paths, at the cost of one extra 4-byte load. Lavapipe pays per load and store
// alike, so there the saving is the count of loads (49 -> 1 per empty cell). Each level is read and written in the
// directions' formats (voxel_images.glsl): packed, a voxel is 5 bytes instead of 8, which a GPU's bandwidth sees.
#extension GL_GOOGLE_include_directive : require
#include "vxgi_types.h"
#include "voxel_images.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(push_constant, scalar) uniform Push { VoxelMipPush p; };

vec4 over(vec4 front, vec4 back) { return front + (1.0 - front.a) * back; }

void main() {
    ivec3 voxel = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(voxel, ivec3(p.dstSize)))) return;
    ivec3 base = voxel * 2;
    if (p.cells != kVoxelNoCells && imageLoad(gVoxelsR32ui[p.cells], voxel).r == 0u) {
        for (uint d = 0; d < 6; ++d) storeDirectionVoxel(p.dst[d], p.dstOpacity[d], voxel, vec4(0.0));
        return;
    }
    for (uint d = 0; d < 6; ++d) {
        int axis = int(d / 2u);
        bool positive = (d & 1u) == 0u;  // travelling towards +axis: the lower child is in front
        ivec3 step = ivec3(0);
        step[axis] = 1;
        ivec3 u = ivec3(0), w = ivec3(0);
        u[(axis + 1) % 3] = 1;
        w[(axis + 2) % 3] = 1;
        vec4 sum = vec4(0.0);
        for (int i = 0; i < 4; ++i) {
            ivec3 c = base + u * (i & 1) + w * (i >> 1);
            vec4 lo = loadDirectionVoxel(p.src[d], p.srcOpacity[d], c);
            vec4 hi = loadDirectionVoxel(p.src[d], p.srcOpacity[d], c + step);
            sum += positive ? over(lo, hi) : over(hi, lo);
        }
        storeDirectionVoxel(p.dst[d], p.dstOpacity[d], voxel, sum * 0.25);
    }
}
