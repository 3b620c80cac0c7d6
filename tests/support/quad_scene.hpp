// quad_scene.hpp: the flat-quad scene builder moved to engine/conformance/quad_scene.hpp (the VXGI conformance
// check builds its scene with it); the tests keep using it under idk::test.
#pragma once
#include "conformance/quad_scene.hpp"

namespace idk::test {
using conformance::makeQuadScene;
using conformance::QuadSpec;
}  // namespace idk::test
