#version 460
// gbuffer_mesh.mesh.glsl: one meshlet per workgroup: its vertices pulled and transformed exactly as
// scene_vertex.glsl does for the MDI rung (same expressions, so both rungs rasterize the same positions and
// varyings), its byte-packed triangles unpacked. Feeds gbuffer.frag unchanged. Ports IDKEngine's
// GBuffer/MeshPath/mesh.glsl (NV) with EXT_mesh_shader.
#extension GL_EXT_mesh_shader : require
#extension GL_GOOGLE_include_directive : require
#include "scene_buffers.glsl"
#include "meshlet_payload.glsl"

layout(local_size_x = kMeshGroupSize) in;
layout(triangles, max_vertices = kMeshletMaxVertices, max_primitives = kMeshletMaxTriangles) out;
layout(push_constant, scalar) uniform Push { GBufferMeshPush p; };
taskPayloadSharedEXT MeshTaskPayload payload;

layout(location = 0) out vec3 outWorldPosition[];
layout(location = 1) out vec3 outNormal[];
layout(location = 2) out vec4 outTangent[];
layout(location = 3) out vec2 outUv[];
layout(location = 4) flat out uint outInstance[];
layout(location = 5) out vec4 outColor[];
layout(location = 6) out vec2 outUv1[];

uint triangleByte(uint byteIndex) {
    return (MeshletWords(p.meshletIndices).data[byteIndex >> 2] >> ((byteIndex & 3u) * 8u)) & 0xFFu;
}

void main() {
    GpuMeshlet m = Meshlets(p.meshlets).data[payload.meshlets[gl_WorkGroupID.x]];
    SetMeshOutputsEXT(m.vertexCount, m.triangleCount);
    GpuInstance instance = InstanceBuffer(p.gbuffer.instances).data[payload.instance];
    mat4 viewProjection = FrameBuffer(p.gbuffer.frame).frame.viewProjection;
    for (uint i = gl_LocalInvocationIndex; i < m.vertexCount; i += kMeshGroupSize) {
        uint vi = uint(int(MeshletWords(p.meshletIndices).data[m.vertexOffset + i]) + payload.vertexOffset);
        GpuVertex v = VertexBuffer(p.gbuffer.vertices).data[vi];
        vec4 world = instance.model * vec4(v.position, 1.0);
        outWorldPosition[i] = world.xyz;
        outNormal[i] = instance.normalMatrix * v.normal;
        outTangent[i] = vec4(mat3(instance.model) * v.tangent.xyz, v.tangent.w);
        outUv[i] = v.uv0;
        outInstance[i] = payload.instance;
        outColor[i] = p.gbuffer.colors != 0 ? Vec4Buffer(p.gbuffer.colors).data[vi] : vec4(1.0);
        outUv1[i] = p.gbuffer.uv1 != 0 ? Vec2Buffer(p.gbuffer.uv1).data[vi] : vec2(0.0);
        gl_MeshVerticesEXT[i].gl_Position = viewProjection * world;
    }
    for (uint t = gl_LocalInvocationIndex; t < m.triangleCount; t += kMeshGroupSize) {
        uint b = m.triangleOffset + 3u * t;
        gl_PrimitiveTriangleIndicesEXT[t] = uvec3(triangleByte(b), triangleByte(b + 1u), triangleByte(b + 2u));
    }
}
