// voxel_list.glsl: the merge's touched-voxel lists (shared/vxgi_types.h kVoxelList*; engine/passes/vxgi_merge.cpp
// says why): reading and writing them through the bindless storage-buffer table.
#ifndef IDK_VOXEL_LIST_GLSL
#define IDK_VOXEL_LIST_GLSL
#include "bindless.glsl"
#include "vxgi_types.h"

IDK_BINDLESS_BUFFER(gVoxelList, uint);

// The entries the list's buffer holds (its descriptor's range sets it: passes::voxelListBytes).
uint voxelListCapacity(uint list) { return uint(gVoxelList[list].data.length()) - kVoxelListHeaderWords; }

// The appends, also those past the capacity.
uint voxelListCount(uint list) { return gVoxelList[list].data[0]; }

// Whether the merge may visit only the lists' entries: there is a previous frame's list (the grid is not new) and
// neither overflowed, so every voxel nonzero in the grid now is in `prevList` and every voxel occupied this frame
// is in `list`.
bool voxelListsComplete(uint list, uint prevList) {
    return list != kVoxelNoList && prevList != kVoxelNoList && voxelListCount(list) <= voxelListCapacity(list) &&
           voxelListCount(prevList) <= voxelListCapacity(prevList);
}

uint packVoxelListEntry(uvec3 voxel) { return voxel.x | (voxel.y << 10) | (voxel.z << 20); }
ivec3 voxelListEntry(uint list, uint i) {
    uint packed = gVoxelList[list].data[kVoxelListHeaderWords + i];
    return ivec3(packed & 0x3FFu, (packed >> 10) & 0x3FFu, packed >> 20);
}
#endif
