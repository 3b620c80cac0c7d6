#version 460
// mask.frag.glsl: alpha MASK in the cascade / spot-map pass (only bound when the scene has MASK materials):
// fragments below the material's cutoff cast no shadow. Ports the alpha test of IDKEngine's shadow fragment shader.
#extension GL_GOOGLE_include_directive : require
#include "shadow_caster.glsl"
#include "shadow_types.h"

layout(push_constant, scalar) uniform Push { ShadowMapPush p; };

void main() {
    if (shadowCasterCutAway(p.instances, p.meshes, p.materials)) discard;
}
