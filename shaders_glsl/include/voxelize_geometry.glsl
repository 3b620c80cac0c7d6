// voxelize_geometry.glsl: the body of the voxelization's geometry shaders (vxgi/voxelize.geom: triangle dilation;
// vxgi/voxelize_axis.geom: the single-draw projection). Per triangle: with push axis kVoxelAxisDominant the
// triangle's own dominant axis is its projection (one draw instead of three; IDKEngine measured three swizzled
// draws faster than this on its GPUs, where VK_NV_geometry_shader_passthrough + VK_NV_viewport_swizzle would be
// the native form), else triangles of another draw's axis are culled. With IDK_VOXELIZE_DILATE each edge moves
// out by the pixel's semi-diagonal along its 2D normal (Crassin & Green, "Octree-Based Sparse Voxelization",
// OpenGL Insights 2012), the new corners are the offset edges' intersections, and every attribute is extrapolated
// affinely (barycentrics of the new corner in the original triangle), so the world position stays on the
// triangle's plane; the fragment shader drops what lies outside the triangle's 2D bounds grown by half a pixel.
#ifndef IDK_VOXELIZE_GEOMETRY_GLSL
#define IDK_VOXELIZE_GEOMETRY_GLSL
#include "vxgi_types.h"
#include "voxelize_projection.glsl"

layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
layout(push_constant, scalar) uniform Push { VoxelizePush p; };

layout(location = 0) in vec3 inWorldPosition[];
layout(location = 1) in vec3 inNormal[];
layout(location = 2) in vec4 inTangent[];
layout(location = 3) in vec2 inUv[];
layout(location = 4) flat in uint inInstance[];
layout(location = 5) in vec4 inColor[];
layout(location = 6) in vec2 inUv1[];

layout(location = 0) out vec3 outWorldPosition;
layout(location = 1) out vec3 outNormal;
layout(location = 2) out vec4 outTangent;
layout(location = 3) out vec2 outUv;
layout(location = 4) flat out uint outInstance;
layout(location = 5) out vec4 outColor;
layout(location = 6) out vec2 outUv1;
#ifdef IDK_VOXELIZE_DILATE
layout(location = 7) flat out vec4 outBounds;  // the triangle's NDC xy bounds grown by half a pixel
#endif

// Emits corner i at barycentrics w of the input triangle (affine in every attribute), at clip position `position`.
void emitCorner(vec3 w, vec4 position) {
    gl_Position = position;
    outWorldPosition = w.x * inWorldPosition[0] + w.y * inWorldPosition[1] + w.z * inWorldPosition[2];
    outNormal = w.x * inNormal[0] + w.y * inNormal[1] + w.z * inNormal[2];
    outTangent = w.x * inTangent[0] + w.y * inTangent[1] + w.z * inTangent[2];
    outUv = w.x * inUv[0] + w.y * inUv[1] + w.z * inUv[2];
    outInstance = inInstance[0];
    outColor = w.x * inColor[0] + w.y * inColor[1] + w.z * inColor[2];
    outUv1 = w.x * inUv1[0] + w.y * inUv1[1] + w.z * inUv1[2];
    EmitVertex();
}

void main() {
    vec3 plane = cross(inWorldPosition[1] - inWorldPosition[0], inWorldPosition[2] - inWorldPosition[0]);
    uint axis = dominantAxis(plane);
    uint drawAxis = p.axis & kVoxelAxisMask;
    if (drawAxis != kVoxelAxisDominant && axis != drawAxis) return;
    // The triangles of other z-slabs (vxgi_memory.hpp) emit nothing.
    vec3 z = (vec3(inWorldPosition[0].z, inWorldPosition[1].z, inWorldPosition[2].z) - p.gridMin.z) / p.voxelSize;
    if (!voxelTriangleInSlab(min(z.x, min(z.y, z.z)), max(z.x, max(z.y, z.z)), p.axis)) return;
    vec4 clip[3];
    for (int i = 0; i < 3; ++i) clip[i] = voxelProjection(inWorldPosition[i], p.gridMin, p.voxelSize, p.gridSize, axis);
#ifndef IDK_VOXELIZE_DILATE
    emitCorner(vec3(1.0, 0.0, 0.0), clip[0]);
    emitCorner(vec3(0.0, 1.0, 0.0), clip[1]);
    emitCorner(vec3(0.0, 0.0, 1.0), clip[2]);
    EndPrimitive();
#else
    vec2 q[3] = vec2[3](clip[0].xy, clip[1].xy, clip[2].xy);
    float area = (q[1].x - q[0].x) * (q[2].y - q[0].y) - (q[2].x - q[0].x) * (q[1].y - q[0].y);
    if (abs(area) < 1e-12) return;  // degenerate in its own dominant projection: no area anywhere
    const float halfPixel = 1.0 / float(p.gridSize);  // NDC spans 2 over gridSize pixels
    float orientation = sign(area);

    // Edge i runs q[i] -> q[i+1]; its outward normal and its offset line n.x = c.
    vec3 lines[3];
    for (int i = 0; i < 3; ++i) {
        vec2 e = q[(i + 1) % 3] - q[i];
        vec2 n = normalize(orientation * vec2(e.y, -e.x));
        lines[i] = vec3(n, dot(n, q[i]) + halfPixel * (abs(n.x) + abs(n.y)));
    }
    outBounds = vec4(min(min(q[0], q[1]), q[2]) - halfPixel, max(max(q[0], q[1]), q[2]) + halfPixel);
    for (int i = 0; i < 3; ++i) {
        // Corner i is where edge i - 1 (into it) and edge i (out of it) meet after the offset.
        vec3 a = lines[(i + 2) % 3], b = lines[i];
        float det = a.x * b.y - a.y * b.x;
        vec2 corner = abs(det) > 1e-12 ? vec2(a.z * b.y - a.y * b.z, a.x * b.z - a.z * b.x) / det : q[i];
        // Barycentrics of the corner in the original triangle (may lie outside [0, 1]).
        float w1 = ((corner.x - q[0].x) * (q[2].y - q[0].y) - (q[2].x - q[0].x) * (corner.y - q[0].y)) / area;
        float w2 = ((q[1].x - q[0].x) * (corner.y - q[0].y) - (corner.x - q[0].x) * (q[1].y - q[0].y)) / area;
        vec3 w = vec3(1.0 - w1 - w2, w1, w2);
        float depth = dot(w, vec3(clip[0].z, clip[1].z, clip[2].z));
        emitCorner(w, vec4(corner, clamp(depth, 0.0, 1.0), 1.0));
    }
    EndPrimitive();
#endif
}

#endif
