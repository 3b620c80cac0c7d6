#version 460
// layers.vert.glsl: vertex pulling for the fixed-layer OIT rung's two raster passes (oit/layers_depth.frag, then
// oit/layers_shade.frag), as transparency/forward.vert but with the rung's wider push block.
// gl_Position is invariant: the shading pass finds its slot by comparing gl_FragCoord.z with the depth the first
// pass stored, so both pipelines must rasterize bit-identical depths (Vulkan promises that only with `invariant`).
#extension GL_GOOGLE_include_directive : require
invariant gl_Position;  // before scene_vertex.glsl writes it (a qualifier cannot change after use)
#include "scene_vertex.glsl"
#include "oit_types.h"

layout(push_constant, scalar) uniform Push { OitLayersPush p; };

void main() {
    emitSceneVertex(uint(gl_InstanceIndex), p.forward.instances, p.forward.vertices, p.forward.colors, p.forward.uv1,
                    p.forward.frame);
}
