#version 460
// gbuffer.frag.glsl: samples the material (bindless textures with KHR_texture_transform), applies alpha MASK,
// single-/double-sided facing and normal mapping in a proper tangent frame with handedness (vertex tangents,
// or a screen-space cotangent frame when the vertex has none), and writes the G-buffer.
// Ports IDKEngine's GBuffer/fragment.glsl, fixing its normal-map bugs (reference section 5).
#extension GL_GOOGLE_include_directive : require
#include "gbuffer_fragment.glsl"
