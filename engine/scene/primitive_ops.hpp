// primitive_ops.hpp: whole-primitive vertex operations: UV-aligned tangent generation (MikkTSpace-style,
// replacing IDKEngine ModelLoader's tangents synthesised from the normal, which ignored the UVs), flat normals,
// un-sharing and duplicating vertices across every per-vertex array (morph targets and skin data included).
#pragma once

#include <cstdint>

#include "scene/scene.hpp"

namespace idk::scene {

// Calls f(array) for every per-vertex array of the primitive, including each morph target's arrays (each is a
// std::vector of some element type; empty arrays included, the callee skips them as it needs).
template <class F>
void forEachVertexArray(Primitive& prim, F&& f) {
    f(prim.positions);
    f(prim.normals);
    f(prim.uv0);
    f(prim.uv1);
    f(prim.colors);
    f(prim.tangents);
    f(prim.joints);
    f(prim.weights);
    for (auto& target : prim.targets) {
        f(target.positions);
        f(target.normals);
        f(target.tangents);
    }
}

// Appends a copy of vertex `vertex` (every non-empty per-vertex array) and returns its index.
uint32_t appendVertexCopy(Primitive& prim, uint32_t vertex);

// Gives every index its own vertex (vertex i = old vertex indices[i]; indices become 0, 1, 2, ...).
void unshareVertices(Primitive& prim);

// Un-shares the vertices and sets each triangle's normals to its geometric normal (CCW winding); a degenerate
// triangle gets +Z. What glTF asks for when a primitive has no NORMAL.
void makeFlatNormals(Primitive& prim);

// Per-vertex tangents from positions, normals and UV set `uvSet` (0: uv0, 1: uv1), written to prim.tangents
// with tangentsGenerated = true:
//   * each triangle's UV-space tangent T = dP/du = (e1 * dv2 - e2 * dv1) / r, r = du1 dv2 - du2 dv1, and its
//     handedness w = -sign(dot(N, cross(e1, e2)) * r): glTF's UV origin is the image's top-left, so the bitangent
//     w * cross(N, T) must point along -dP/dv (up the image, the normal map's green axis), as the MikkTSpace
//     tangents stored in glTF files do;
//   * per vertex and handedness, T projected onto the normal's tangent plane, normalized and accumulated with the
//     corner angle as weight (as MikkTSpace weights), then normalized again: xyz unit and orthogonal to N;
//   * a vertex used by triangles of both handedness (a mirrored-UV seam) is split: the triangles of the
//     minority sign (ties: the negative one) get a copy of the vertex, so both sides keep their own tangent frame;
//   * triangles with degenerate UVs contribute nothing; a vertex with no contribution gets any unit vector
//     orthogonal to N and w = +1.
// Does nothing (returns 0) when the UV set is empty. Returns the number of vertices added by splitting.
size_t generateTangents(Primitive& prim, uint32_t uvSet = 0);

}  // namespace idk::scene
