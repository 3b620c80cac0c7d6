// scene_invariants.hpp: the promises scene.hpp makes about a loaded Scene (every index in range, per-vertex arrays
// empty or one entry per vertex, triangle lists, one inverse bind matrix per joint, non-decreasing keyframe times),
// checked by the glTF fuzz harness on whatever the loader accepts. Returns the first broken promise, or "".
#pragma once

#include <string>

#include "scene/scene.hpp"

namespace idk::fuzz {

std::string firstBrokenInvariant(const scene::Scene& s);

}  // namespace idk::fuzz
