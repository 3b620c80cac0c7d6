// primitive_ops.cpp: tangent generation (MikkTSpace-style angle-weighted per-vertex accumulation, split at
// mirrored-UV seams), flat normals and vertex un-sharing/duplication over every per-vertex array. Replaces the
// normal-derived tangents of IDKEngine's ModelLoader (internals report section 5: not UV-aligned, no sign).
#include "scene/primitive_ops.hpp"

#include <algorithm>
#include <cmath>

namespace idk::scene {

uint32_t appendVertexCopy(Primitive& prim, uint32_t vertex) {
    const auto index = uint32_t(prim.positions.size());
    forEachVertexArray(prim, [&](auto& array) {
        if (!array.empty()) array.push_back(array[vertex]);
    });
    return index;
}

void unshareVertices(Primitive& prim) {
    forEachVertexArray(prim, [&](auto& array) {
        if (array.empty()) return;
        std::remove_reference_t<decltype(array)> out(prim.indices.size());
        for (size_t i = 0; i < prim.indices.size(); ++i) out[i] = array[prim.indices[i]];
        array = std::move(out);
    });
    for (size_t i = 0; i < prim.indices.size(); ++i) prim.indices[i] = uint32_t(i);
}

void makeFlatNormals(Primitive& prim) {
    if (prim.normals.size() != prim.positions.size()) prim.normals.assign(prim.positions.size(), glm::vec3(0.0f));
    unshareVertices(prim);
    for (size_t t = 0; t + 2 < prim.indices.size(); t += 3) {
        const glm::vec3 a = prim.positions[t], b = prim.positions[t + 1], c = prim.positions[t + 2];
        const glm::vec3 cr = glm::cross(b - a, c - a);
        const float len = glm::length(cr);
        const glm::vec3 normal = (len > 0.0f && std::isfinite(len)) ? cr / len : glm::vec3(0.0f, 0.0f, 1.0f);
        for (size_t k = 0; k < 3; ++k) prim.normals[t + k] = normal;
    }
}

namespace {

// Any unit vector orthogonal to n (n need not be unit; a zero n gives +X).
glm::vec3 anyPerpendicular(const glm::vec3& n) {
    const glm::vec3 axis = std::abs(n.x) < 0.9f * glm::length(n) ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    const glm::vec3 t = glm::cross(n, axis);
    const float len = glm::length(t);
    return len > 0.0f && std::isfinite(len) ? t / len : glm::vec3(1, 0, 0);
}

// The unit part of v orthogonal to unit n, or nothing when v (nearly) lies along n.
bool projectOntoPlane(const glm::vec3& v, const glm::vec3& n, glm::vec3& out) {
    const glm::vec3 p = v - n * glm::dot(n, v);
    const float len = glm::length(p);
    if (!(len > 1e-20f) || !std::isfinite(len)) return false;
    out = p / len;
    return true;
}

float cornerAngle(const glm::vec3& p, const glm::vec3& next, const glm::vec3& prev) {
    const glm::vec3 a = next - p, b = prev - p;
    const float la = glm::length(a), lb = glm::length(b);
    if (!(la > 0.0f && lb > 0.0f) || !std::isfinite(la * lb)) return 0.0f;
    return std::acos(std::clamp(glm::dot(a, b) / (la * lb), -1.0f, 1.0f));
}

glm::vec3 unitNormal(const glm::vec3& n) {
    const float len = glm::length(n);
    return len > 0.0f && std::isfinite(len) ? n / len : glm::vec3(0.0f);
}

}  // namespace

size_t generateTangents(Primitive& prim, uint32_t uvSet) {
    const std::vector<glm::vec2>& uvs = uvSet == 0 ? prim.uv0 : prim.uv1;
    const size_t vertexCount = prim.positions.size();
    if (uvs.size() != vertexCount || vertexCount == 0 || prim.normals.size() != vertexCount) return 0;

    // Pass 1: per corner, the triangle's handedness and angle-weighted tangent, accumulated per vertex and sign.
    const size_t cornerCount = prim.indices.size() - prim.indices.size() % 3;
    std::vector<int8_t> cornerSign(cornerCount, 0);
    std::vector<glm::vec3> accumulated[2] = {std::vector<glm::vec3>(vertexCount, glm::vec3(0.0f)),
                                             std::vector<glm::vec3>(vertexCount, glm::vec3(0.0f))};  // [0] +, [1] -
    std::vector<uint32_t> signCount[2] = {std::vector<uint32_t>(vertexCount, 0u),
                                          std::vector<uint32_t>(vertexCount, 0u)};
    for (size_t t = 0; t < cornerCount; t += 3) {
        const uint32_t i[3] = {prim.indices[t], prim.indices[t + 1], prim.indices[t + 2]};
        const glm::vec3 e1 = prim.positions[i[1]] - prim.positions[i[0]];
        const glm::vec3 e2 = prim.positions[i[2]] - prim.positions[i[0]];
        const glm::vec2 d1 = uvs[i[1]] - uvs[i[0]];
        const glm::vec2 d2 = uvs[i[2]] - uvs[i[0]];
        const float r = d1.x * d2.y - d2.x * d1.y;
        if (!(std::abs(r) > 1e-20f) || !std::isfinite(r)) continue;  // degenerate UVs: no tangent direction
        const glm::vec3 faceTangent = (e1 * d2.y - e2 * d1.y) / r;
        const glm::vec3 geometric = glm::cross(e1, e2);
        for (int k = 0; k < 3; ++k) {
            const uint32_t v = i[k];
            const glm::vec3 n = unitNormal(prim.normals[v]);
            // glTF's UV origin is the image's top-left, so the bitangent (the normal map's green axis, up the
            // image) is -dP/dv: w = +1 when cross(N, T) points along -dP/dv, i.e. when the UV triangle winds
            // opposite to the geometry as seen from N (MikkTSpace tangents in glTF files follow this).
            const float orientation = glm::dot(n, geometric) * r;
            const int8_t sign = orientation > 0.0f ? int8_t(-1) : int8_t(1);
            cornerSign[t + size_t(k)] = sign;
            const int slot = sign > 0 ? 0 : 1;
            ++signCount[slot][v];
            glm::vec3 projected;
            if (!projectOntoPlane(faceTangent, n, projected)) continue;
            const float angle =
                cornerAngle(prim.positions[v], prim.positions[i[(k + 1) % 3]], prim.positions[i[(k + 2) % 3]]);
            accumulated[slot][v] += angle * projected;
        }
    }

    // Pass 2: split vertices used with both signs; the minority sign's corners move to a copy.
    prim.tangents.clear();  // rebuilt below; keeps appendVertexCopy from copying stale values
    std::vector<int8_t> vertexSign(vertexCount, 0);
    std::vector<uint32_t> copyOf(vertexCount, UINT32_MAX);
    size_t added = 0;
    for (uint32_t v = 0; v < vertexCount; ++v) {
        const uint32_t plus = signCount[0][v], minus = signCount[1][v];
        vertexSign[v] = minus > plus ? int8_t(-1) : int8_t(1);
        if (plus > 0 && minus > 0) {
            copyOf[v] = appendVertexCopy(prim, v);
            ++added;
        }
    }
    for (size_t c = 0; c < cornerCount; ++c) {
        const uint32_t v = prim.indices[c];
        if (v < vertexCount && copyOf[v] != UINT32_MAX && cornerSign[c] != 0 && cornerSign[c] != vertexSign[v])
            prim.indices[c] = copyOf[v];
    }

    // Pass 3: normalize, Gram-Schmidt against the normal, attach the sign.
    const size_t total = prim.positions.size();
    prim.tangents.assign(total, glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));
    auto finish = [&](uint32_t out, const glm::vec3& sum, int8_t sign) {
        const glm::vec3 n = unitNormal(prim.normals[out]);
        glm::vec3 t;
        if (!projectOntoPlane(sum, n, t)) {
            t = anyPerpendicular(n);
            sign = 1;
        }
        prim.tangents[out] = glm::vec4(t, float(sign));
    };
    for (uint32_t v = 0; v < vertexCount; ++v) {
        const int8_t sign = vertexSign[v];
        finish(v, accumulated[sign > 0 ? 0 : 1][v], sign);
        if (copyOf[v] != UINT32_MAX) finish(copyOf[v], accumulated[sign > 0 ? 1 : 0][v], int8_t(-sign));
    }
    prim.tangentsGenerated = true;
    return added;
}

}  // namespace idk::scene
