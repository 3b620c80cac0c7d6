// workgroup_scan.glsl: exclusive prefix sum of one uint per invocation across a workgroup: subgroup scans, then
// the first subgroup scans the per-subgroup totals kept in shared memory. Correct for any subgroup size: the
// includer declares the spec constant kMinSubgroupSize (the device's minimum subgroup size, see
// engine/render/compute_primitives.cpp), which sizes the shared slots for the most subgroups a workgroup can have.
// Must be reached in uniform control flow (it contains barriers).
#ifndef IDK_WORKGROUP_SCAN_GLSL
#define IDK_WORKGROUP_SCAN_GLSL
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require

shared uint sScanSlots[(gl_WorkGroupSize.x + kMinSubgroupSize - 1) / kMinSubgroupSize];
shared uint sScanTotal;

uint workgroupExclusiveAdd(uint value, out uint workgroupTotal) {
    uint inSubgroup = subgroupExclusiveAdd(value);
    uint subgroupTotal = subgroupAdd(value);
    if (subgroupElect()) sScanSlots[gl_SubgroupID] = subgroupTotal;
    // SYNC: the per-subgroup totals are written before the first subgroup scans them.
    barrier();
    if (gl_SubgroupID == 0) {
        uint carry = 0;
        for (uint base = 0; base < gl_NumSubgroups; base += gl_SubgroupSize) {
            uint s = base + gl_SubgroupInvocationID;
            uint total = s < gl_NumSubgroups ? sScanSlots[s] : 0;
            if (s < gl_NumSubgroups) sScanSlots[s] = carry + subgroupExclusiveAdd(total);
            carry += subgroupAdd(total);
        }
        if (subgroupElect()) sScanTotal = carry;
    }
    // SYNC: the scanned totals are written before every subgroup reads its own.
    barrier();
    workgroupTotal = sScanTotal;
    return sScanSlots[gl_SubgroupID] + inSubgroup;
}

uint workgroupExclusiveAdd(uint value) {
    uint unusedTotal;
    return workgroupExclusiveAdd(value, unusedTotal);
}

#endif
