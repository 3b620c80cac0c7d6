// animation.hpp: CPU animation of a loaded Scene at an explicit time (the port of IDKEngine's animation update,
// plus what it lacks: CUBICSPLINE, morph weights): keyframe sampling, node TRS / weights, world and joint
// matrices; and the CPU reference for the vertex deformation (morph + skin) that the GPU skinning pass performs.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.hpp"

namespace idk::scene {

// Poses the scene at `timeSeconds`: every node is reset to its rest pose (Node::rest), then every channel of
// animation `animation` (-1: all, in file order; a later channel on the same node and path wins) writes its
// sampled value, then updateTransforms() recomputes world matrices, instances, cameras, lights and joint
// matrices. A pure function of the loaded scene and its arguments: the same time gives bit-identical results.
// Sampling (glTF 2.0, appendix C):
//   * t is clamped to each sampler's [first, last] keyframe time (no looping: callers wrap time if they want);
//   * STEP: the value of the keyframe at or before t;
//   * LINEAR: lerp; rotations slerp on the shorter arc (q1 negated when dot < 0), normalized;
//   * CUBICSPLINE: Hermite with tangents scaled by the keyframe interval,
//       p = (2s^3 - 3s^2 + 1) v_k + (s^3 - 2s^2 + s) td b_k + (-2s^3 + 3s^2) v_k+1 + (s^3 - s^2) td a_k+1,
//     rotations normalized afterwards.
// Throws std::out_of_range for an animation index >= scene.animations.size().
void evaluateAnimations(Scene& scene, double timeSeconds, int animation = -1);

// One sampler's value at time t as evaluateAnimations() computes it: `components` floats (a unit x, y, z, w
// quaternion for rotations when `isRotation`).
std::vector<float> sampleAnimation(const AnimationSampler& sampler, double t, bool isRotation);

// Where vertex `vertex` of `prim` (a primitive of instance.mesh) ends up in world space with the node's current
// morph weights and joint matrices: world * skin * (position + sum_i weight_i * target_i.position), where
// skin = sum_c weights[c] * jointMatrices[joints[c]] when the node is skinned and the primitive has JOINTS_0.
glm::vec3 deformedPosition(const Scene& scene, const Instance& instance, const Primitive& prim, uint32_t vertex);

}  // namespace idk::scene
