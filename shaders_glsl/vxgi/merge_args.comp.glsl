#version 460
// merge_args.comp.glsl: the indirect dispatch of a slab's merge (merge.comp.glsl): over the entries of the previous
// frame's touched-voxel list and this frame's so far, (previous + current) / kVoxelListGroup workgroups in rows of
// at most 32768 (maxComputeWorkGroupCount[0] is only guaranteed 65535), or over the slab's every voxel where the
// lists are incomplete (voxelListsComplete: an overflow, or no previous list). One invocation. No IDKEngine
// counterpart: its merge visits every voxel.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#include "voxel_list.glsl"

layout(buffer_reference, scalar, buffer_reference_align = 4) writeonly buffer DispatchRef { uint xyz[3]; };

layout(local_size_x = 1) in;
layout(push_constant, scalar) uniform Push { VoxelMergeArgsPush p; };

uint groups(uint n, uint size) { return (n + size - 1u) / size; }

void main() {
    uvec3 dispatch;
    if (voxelListsComplete(p.list, p.prevList)) {
        uint g = groups(voxelListCount(p.prevList) + voxelListCount(p.list), kVoxelListGroup);
        dispatch = uvec3(min(g, 32768u), groups(g, 32768u), 1u);
    } else {
        dispatch = uvec3(groups(p.gridSize, kVoxelGroupSize), groups(p.gridSize, kVoxelGroupSize),
                         groups(p.slabDepth, kVoxelGroupSize));
    }
    DispatchRef args = DispatchRef(p.args);
    args.xyz[0] = dispatch.x;
    args.xyz[1] = dispatch.y;
    args.xyz[2] = dispatch.z;
}
