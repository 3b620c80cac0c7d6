#version 460
// mask.frag.glsl: alpha MASK in the point-shadow pass: fragments whose base-colour alpha is below the material's
// cutoff cast no shadow. Only bound when the scene has MASK materials (the pass is depth-only otherwise).
// Ports the alpha test of IDKEngine's PointShadow/fragment.glsl.
#extension GL_GOOGLE_include_directive : require
#include "shadow_caster.glsl"
#include "shadow_types.h"

layout(push_constant, scalar) uniform Push { PointShadowPush p; };

void main() {
    if (shadowCasterCutAway(p.instances, p.meshes, p.materials)) discard;
}
