// culling_types.h: what the GPU culling pass reads and writes (engine/frame/culling_feature.cpp packs it): one
// GpuCullDraw per scene draw (its object-space box and index range), one GpuCullView per view (world-space frustum
// planes), and the push block. The box test is defined here once for the kernel (culling/cull_instances.comp.glsl)
// and its C++ oracle (render/culling_math.cpp). Ports the inputs of IDKEngine's MeshCulling/Camera/Cull/compute.glsl.
#ifndef IDK_CULLING_TYPES_H
#define IDK_CULLING_TYPES_H
#include "interop.h"

IDK_GPU_BEGIN

IDK_CONST(uint, kCullGroupSize, 64);  // invocations per workgroup (IDKEngine: 64), one draw each

IDK_CONST(uint, kCullSkip, 1u);         // GpuCullDraw::flags: never drawn by this pass (BLEND draws)
IDK_CONST(uint, kCullAlwaysVisible, 2u);  // no trustworthy box (skinned/morphed vertices move at run time)
IDK_CONST(uint, kCullSingleSided, 4u);    // the material is single-sided: its meshlets may be normal-cone culled

// One scene draw as the culling pass sees it: draw i places GpuInstance i.
struct GpuCullDraw {
    vec3 boxCenter;  // object space
    uint indexCount;
    vec3 boxExtent;  // object space half size (>= 0)
    uint firstIndex;
    int vertexOffset;
    uint flags;      // kCull*
    uint firstMeshlet;  // mesh rung: the mesh's meshlets (shared/meshlet_types.h)
    uint meshletCount;
    // Mesh rung: the first word of this draw's meshlet visibility bits (bit j of word w + k: meshlet 32 k + j of
    // the draw drawn last frame). One word per task workgroup (kTaskGroupSize = 32 meshlets), so each workgroup
    // owns its word and writes it without atomics.
    uint meshletVisibilityWord;
};
IDK_GPU_SIZE(GpuCullDraw, 52);

// One view: six world-space planes (xyz normal pointing inside, w offset), inside when dot(n, p) + w >= 0.
// Extracted from the view-projection matrix (Gribb-Hartmann, Vulkan depth 0..1): left, right, top, bottom, near,
// far. An infinite far plane comes out as (0, 0, 0, n > 0), which every box passes.
// The Hi-Z test (phase kCullLate) projects boxes with viewProjection onto a viewport of `viewport` pixels.
struct GpuCullView {
    vec4 planes[6];
    mat4 viewProjection;
    uvec2 viewport;
    uint pad0, pad1;
};
IDK_GPU_SIZE(GpuCullView, 176);

// CullPush::phase. Two-phase occlusion culling (niagara's approach): the early phase draws what was visible last
// frame (frustum only), the late phase tests every draw against the Hi-Z pyramid of the early phase's depth,
// records the result as next frame's visibility, and draws what passes but the early phase did not draw.
// On the mesh rung the same holds per meshlet: the early phase launches the instances visible last frame and their
// task shader draws only the meshlets whose bit is set; the late phase launches every instance that passes (also
// those drawn early, marked kDrawnEarly in drawInstance) and its task shader tests each meshlet (frustum, normal
// cone, Hi-Z), rewrites the meshlet's bit, and draws it unless the early phase drew it.
IDK_CONST(uint, kCullFrustum, 0);  // frustum only, no visibility bits
IDK_CONST(uint, kCullEarly, 1);
IDK_CONST(uint, kCullLate, 2);
IDK_CONST(uint, kDrawnEarly, 0x80000000u);  // drawInstance flag (mesh rung, late phase): the early phase drew it

// The counters the pass writes; drawCount is the vkCmdDrawIndexedIndirectCount count (it must stay first).
struct GpuCullCounters {
    uint drawCount;         // commands written = instances drawn
    uint instancesTested;   // draws that were tested (not kCullSkip)
    uint trianglesDrawn;    // MDI: indexCount / 3 of the drawn commands; mesh rung: triangles of drawn meshlets
    uint meshletsTested;    // mesh rung (task shader): meshlets of the launched instances it tested (early: those
                            // with their bit set; late: those the early phase did not draw)
    uint meshletsDrawn;     // mesh rung: meshlets that passed frustum, normal cone (and Hi-Z in the late phase)
    uint relaunched;        // mesh rung, late phase: commands of instances the early phase drew already (their
                            // meshlets not drawn early are tested again); drawCount - relaunched were newly drawn
    uint pad1, pad2;
};
IDK_GPU_SIZE(GpuCullCounters, 32);

struct CullPush {
    DeviceAddress instances;     // GpuInstance[drawCount] (the scene's, after this frame's pose upload)
    DeviceAddress draws;         // GpuCullDraw[drawCount]
    DeviceAddress views;         // GpuCullView[]
    DeviceAddress commands;      // out: VkDrawIndexedIndirectCommand[drawCount] (the first counters.drawCount used),
                                 // firstInstance = the instance it draws
    DeviceAddress counters;      // GpuCullCounters, zeroed before the pass
    DeviceAddress visibility;    // uint[drawCount], 1 = drawn last frame (kCullEarly reads, kCullLate rewrites)
    DeviceAddress pyramid;       // float[]: the Hi-Z pyramid of the early phase's depth (kCullLate; depth_pyramid.h)
    DeviceAddress drawInstance;  // meshTasks: out: uint[drawCount], the instance of each command (| kDrawnEarly)
    uint drawCount;
    uint view;                   // index into views
    uint phase;                  // kCull*
    uint meshTasks;              // 1: write MeshTaskCommands (mesh rung) instead of VkDrawIndexedIndirectCommands
};
IDK_GPU_SIZE(CullPush, 80);

// The world box of an object box under `model` (centre transformed, extent through |mat3(model)|): a box that
// contains every transformed point of the object box (conservative, exact for axis-aligned transforms).
IDK_INLINE void worldBox(mat4 model, vec3 center, vec3 extent, IDK_OUT(vec3) worldCenter, IDK_OUT(vec3) worldExtent) {
    worldCenter = vec3(model * vec4(center, 1.0f));
    worldExtent = abs(vec3(model[0])) * extent.x + abs(vec3(model[1])) * extent.y + abs(vec3(model[2])) * extent.z;
}

// False only when the box lies entirely on the outer side of one plane (then no point of it can be drawn).
IDK_INLINE bool boxInFrustum(GpuCullView view, vec3 center, vec3 extent) {
    for (int i = 0; i < 6; ++i) {
        vec3 n = vec3(view.planes[i]);
        if (dot(n, center) + dot(abs(n), extent) + view.planes[i].w < 0.0f) return false;
    }
    return true;
}

IDK_GPU_END
#endif
