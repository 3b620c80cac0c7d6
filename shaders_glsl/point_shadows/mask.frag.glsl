#version 460
// mask.frag.glsl: alpha MASK in the point-shadow pass: fragments whose base-colour alpha is below the material's
// cutoff cast no shadow. Only bound when the scene has MASK materials (the pass is depth-only otherwise).
// Ports the alpha test of IDKEngine's PointShadow/fragment.glsl.
#extension GL_GOOGLE_include_directive : require
#include "scene_buffers.glsl"
#include "bindless.glsl"
#include "shadow_types.h"

layout(push_constant, scalar) uniform Push { PointShadowPush p; };

layout(location = 0) in vec2 inUv;
layout(location = 1) in vec2 inUv1;
layout(location = 2) in float inAlpha;
layout(location = 3) flat in uint inDraw;

void main() {
    GpuInstance instance = InstanceBuffer(p.instances).data[inDraw];
    GpuMaterial m = MaterialBuffer(p.materials).data[MeshBuffer(p.meshes).data[instance.mesh].material];
    if (m.alphaMode != kAlphaMask) return;
    GpuTextureSlot slot = m.slots[kSlotBaseColor];
    vec3 h = vec3(slot.texCoord == 1u ? inUv1 : inUv, 1.0);
    vec2 st = vec2(dot(slot.row0, h), dot(slot.row1, h));
    float alpha = m.baseColorFactor.a * inAlpha * IDK_SAMPLE_2D(slot.texture, slot.samplerIndex, st).a;
    if (alpha < m.alphaCutoff) discard;
}
