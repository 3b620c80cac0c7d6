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
    if (!voxelFragment(voxel, radiance)) discard;
    appendVoxelRecord(voxel, radiance);
}
