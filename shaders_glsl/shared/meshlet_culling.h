// meshlet_culling.h: the mesh rung's per-meshlet tests before Hi-Z (gbuffer/gbuffer_mesh.task.glsl), one source
// for the task shader and its CPU oracle (render::meshletOracle): the bounding sphere against the view's planes and
// the normal cone (meshoptimizer's test) against the eye. Ports the meshlet tests of IDKEngine's
// GBuffer/MeshPath/task.glsl, with the normal cone added.
#ifndef IDK_MESHLET_CULLING_H
#define IDK_MESHLET_CULLING_H
#include "interop.h"
#include "culling_types.h"
#include "meshlet_types.h"

IDK_GPU_BEGIN

// The world bounding sphere of meshlet `m` under `model` (radius scaled by the largest axis scale: conservative).
IDK_INLINE void meshletSphere(GpuMeshlet m, mat4 model, IDK_OUT(vec3) center, IDK_OUT(float) radius) {
    vec3 scale = vec3(length(vec3(model[0])), length(vec3(model[1])), length(vec3(model[2])));
    center = vec3(model * vec4(m.center, 1.0f));
    float largest = scale.x > scale.y ? scale.x : scale.y;
    radius = m.radius * (largest > scale.z ? largest : scale.z);
}

// The world box of meshlet `m`'s vertex box under `model` (the late phase tests it against the Hi-Z pyramid).
IDK_INLINE void meshletBox(GpuMeshlet m, mat4 model, IDK_OUT(vec3) center, IDK_OUT(vec3) extent) {
    worldBox(model, m.boxCenter, m.boxExtent, center, extent);
}

// False when the meshlet cannot be seen from `eye` through `view`: its sphere is outside a plane, or (single-sided
// material, perspective view, no mirroring, uniform scale: a non-uniform scale bends normals away from the cone)
// every triangle faces away from the eye. `drawFlags`: GpuCullDraw::flags (kCullAlwaysVisible: never culled).
IDK_INLINE bool meshletInView(GpuMeshlet m, uint drawFlags, mat4 model, GpuCullView view, vec3 eye) {
    if ((drawFlags & kCullAlwaysVisible) != 0u) return true;  // deformed vertices: the bounds do not hold
    vec3 center;
    float radius;
    meshletSphere(m, model, center, radius);
    for (int i = 0; i < 6; ++i) {
        vec4 plane = view.planes[i];
        if (dot(vec3(plane), center) + plane.w < -radius * length(vec3(plane))) return false;
    }
    vec3 scale = vec3(length(vec3(model[0])), length(vec3(model[1])), length(vec3(model[2])));
    bool perspective = view.viewProjection[0][3] != 0.0f || view.viewProjection[1][3] != 0.0f ||
                       view.viewProjection[2][3] != 0.0f;
    float tolerance = 1e-4f * scale.x;  // |a - b| <= t written without abs (C++ would find the integer one)
    bool uniformScale = scale.x - scale.y <= tolerance && scale.y - scale.x <= tolerance &&
                        scale.x - scale.z <= tolerance && scale.z - scale.x <= tolerance;
    bool mirrored = determinant(mat3(model)) < 0.0f;
    if ((drawFlags & kCullSingleSided) != 0u && perspective && uniformScale && !mirrored && m.coneCutoff < 1.0f) {
        vec3 apex = vec3(model * vec4(m.coneApex, 1.0f));
        vec3 axis = normalize(mat3(model) * m.coneAxis);
        if (dot(normalize(apex - eye), axis) >= m.coneCutoff) return false;
    }
    return true;
}

IDK_GPU_END
#endif
