#version 460
// voxelize_record.frag.glsl: gl-interop rung of "vxgi-atomics": each fragment appends one record (its voxel and
// premultiplied rgba, coverage 1) to a buffer shared with OpenGL, whose compute pass adds the records into the voxels
// with GL atomics (engine/passes/vxgi_gl_accumulate.cpp). The counter counts past the capacity: the host sees the
// overflow and grows the buffer (records past it are not written).
#extension GL_GOOGLE_include_directive : require
#include "voxelize_fragment.glsl"
#include "voxelize_record.glsl"

void main() {
    ivec3 voxel;
    vec3 radiance;
    vec4 facing;
    if (!voxelFragment(voxel, radiance, facing)) discard;
    appendVoxelRecord(voxel, radiance, facing);
}
