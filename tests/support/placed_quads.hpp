// placed_quads.hpp: the placed-quad scenes and CPU ray cast moved to engine/conformance/placed_quads.hpp (the VXGI
// conformance check builds its scene with them); the tests keep using them under idk::test.
#pragma once
#include "conformance/placed_quads.hpp"

namespace idk::test {
using conformance::boxFaces;
using conformance::castRay;
using conformance::makePlacedQuadScene;
using conformance::PlacedQuad;
using conformance::placedQuad;
using conformance::pointLight;
using conformance::RayHit;
}  // namespace idk::test
