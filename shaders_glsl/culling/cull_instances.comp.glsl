#version 460
// cull_instances.comp.glsl: one invocation per scene draw for one view: the frustum test of the instance's world
// box, and in the late phase of two-phase occlusion culling the Hi-Z test (shared/depth_pyramid.h); survivors
// append a VkDrawIndexedIndirectCommand whose firstInstance names the instance (the vertex shader's
// gl_InstanceIndex) and count themselves in the counters that vkCmdDrawIndexedIndirectCount reads. On the mesh
// rung the late phase also relaunches the visible draws the early phase drew (the task shader tests their other
// meshlets). Ports IDKEngine's MeshCulling/Camera/Cull/compute.glsl (there: atomicAdd into a per-mesh
// instanceCount, commands re-uploaded by the CPU every pass; here: compacted commands and a GPU count).
#extension GL_GOOGLE_include_directive : require
#include "scene_buffers.glsl"
#include "culling_types.h"
#include "depth_pyramid.h"
#include "meshlet_types.h"

layout(local_size_x = kCullGroupSize) in;
layout(push_constant, scalar) uniform Push { CullPush p; };

struct DrawCommand {
    uint indexCount;
    uint instanceCount;
    uint firstIndex;
    int vertexOffset;
    uint firstInstance;
};
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer CullDraws { GpuCullDraw data[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer CullViews { GpuCullView data[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) writeonly buffer Commands { DrawCommand data[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) writeonly buffer TaskCommands { MeshTaskCommand data[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) writeonly buffer DrawInstances { uint data[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Counters { GpuCullCounters c; };
layout(buffer_reference, scalar, buffer_reference_align = 4) buffer Visibility { uint data[]; };
layout(buffer_reference, scalar, buffer_reference_align = 4) readonly buffer Pyramid { float data[]; };

// False only when every pixel the box covers already holds something nearer (the pyramid's farthest depth over
// the footprint is nearer than the box's nearest point).
bool hizVisible(GpuCullView view, vec3 center, vec3 extent) {
    vec4 rect;
    float nearest;
    if (!hizFootprint(view.viewProjection, center, extent, vec2(view.viewport), rect, nearest)) return true;
    uvec4 t;
    uint level = hizTexels(rect, view.viewport, t);
    uint offset = hizLevelOffset(view.viewport, level);
    uint width = hizLevelSize(view.viewport, level).x;
    Pyramid pyramid = Pyramid(p.pyramid);
    float farthest = max(max(pyramid.data[offset + t.y * width + t.x], pyramid.data[offset + t.y * width + t.z]),
                         max(pyramid.data[offset + t.w * width + t.x], pyramid.data[offset + t.w * width + t.z]));
    return nearest <= farthest;
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= p.drawCount) return;
    GpuCullDraw d = CullDraws(p.draws).data[i];
    if ((d.flags & kCullSkip) != 0u) return;
    // One atomic per tested draw keeps the stats exact; a real GPU would sum per subgroup first (subgroupAdd).
    atomicAdd(Counters(p.counters).c.instancesTested, 1u);
    bool visible = true;
    if ((d.flags & kCullAlwaysVisible) == 0u) {
        GpuCullView view = CullViews(p.views).data[p.view];
        vec3 center, extent;
        worldBox(InstanceBuffer(p.instances).data[i].model, d.boxCenter, d.boxExtent, center, extent);
        visible = boxInFrustum(view, center, extent) && (p.phase != kCullLate || hizVisible(view, center, extent));
    }
    bool relaunch = false;  // mesh rung, late phase: drawn early, launched again for its remaining meshlets
    if (p.phase != kCullFrustum) {
        bool drawnEarly = Visibility(p.visibility).data[i] != 0u;  // early: drawn if in the frustum
        if (p.phase == kCullLate) Visibility(p.visibility).data[i] = visible ? 1u : 0u;
        // Late and visible implies in the frustum, so drawnEarly here means the early phase drew it.
        relaunch = p.phase == kCullLate && drawnEarly && p.meshTasks != 0u;
        if (p.phase == kCullEarly ? !drawnEarly : drawnEarly && !relaunch) visible = false;
    }
    if (!visible) return;
    if (relaunch) atomicAdd(Counters(p.counters).c.relaunched, 1u);
    // The order of the compacted commands varies between runs; the image does not (depth test LESS, and each
    // pixel's nearest fragment does not depend on draw order unless two fragments tie exactly in depth).
    uint slot = atomicAdd(Counters(p.counters).c.drawCount, 1u);
    if (p.meshTasks == 0u) atomicAdd(Counters(p.counters).c.trianglesDrawn, d.indexCount / 3u);  // else per meshlet
    if (p.meshTasks != 0u) {
        TaskCommands(p.commands).data[slot] = MeshTaskCommand((d.meshletCount + kTaskGroupSize - 1u) / kTaskGroupSize, 1u, 1u);
        DrawInstances(p.drawInstance).data[slot] = relaunch ? i | kDrawnEarly : i;
    } else {
        Commands(p.commands).data[slot] = DrawCommand(d.indexCount, 1u, d.firstIndex, d.vertexOffset, i);
    }
}
