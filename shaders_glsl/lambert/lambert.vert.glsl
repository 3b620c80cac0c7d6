#version 460
// lambert.vert.glsl: pulls a pre-transformed vertex from a bindless buffer (no vertex input state) and projects it.
#extension GL_GOOGLE_include_directive : require
#include "interop.h"
#include "bindless.glsl"
#include "lambert_types.h"

layout(push_constant, scalar) uniform Push { LambertPush p; };
IDK_BINDLESS_BUFFER_READONLY(gVertices, GpuLambertVertex);

layout(location = 0) out vec3 outPosition;
layout(location = 1) out vec3 outNormal;
layout(location = 2) flat out uint outMaterial;

void main() {
    GpuLambertVertex v = gVertices[p.vertexBuffer].data[gl_VertexIndex];
    outPosition = v.position;
    outNormal = v.normal;
    outMaterial = v.material;
    gl_Position = p.viewProjection * vec4(v.position, 1.0);
}
