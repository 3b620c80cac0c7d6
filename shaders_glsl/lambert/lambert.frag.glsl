#version 460
// lambert.frag.glsl: Lambert diffuse (albedo / pi) from point lights with inverse-square falloff, plus a constant
// ambient term and emission. Writes linear HDR radiance. Faces are lit from the side the camera sees.
#extension GL_GOOGLE_include_directive : require
#include "interop.h"
#include "bindless.glsl"
#include "lambert_types.h"

layout(push_constant, scalar) uniform Push { LambertPush p; };
IDK_BINDLESS_BUFFER_READONLY(gMaterials, GpuLambertMaterial);
IDK_BINDLESS_BUFFER_READONLY(gLights, GpuLambertLight);

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) flat in uint inMaterial;
layout(location = 0) out vec4 outColor;

const float kPi = 3.14159265358979;

void main() {
    GpuLambertMaterial m = gMaterials[p.materialBuffer].data[inMaterial];
    vec3 n = normalize(inNormal);
    if (!gl_FrontFacing) n = -n;  // double-sided walls
    vec3 radiance = m.emissive + m.albedo * p.ambient;
    for (uint i = 0; i < min(p.lightCount, kLambertMaxLights); ++i) {
        GpuLambertLight light = gLights[p.lightBuffer].data[i];
        vec3 toLight = light.position - inPosition;
        float distanceSquared = max(dot(toLight, toLight), 1e-8);
        float cosTheta = max(dot(n, toLight * inversesqrt(distanceSquared)), 0.0);
        radiance += (m.albedo / kPi) * light.intensity * cosTheta / distanceSquared;
    }
    outColor = vec4(radiance, 1.0);
}
