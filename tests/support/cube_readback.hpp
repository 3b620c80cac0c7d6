// cube_readback.hpp: readCube moved to engine/conformance/cube_readback.hpp (a registered check reads cubes too);
// the tests keep using it under idk::test.
#pragma once
#include "conformance/cube_readback.hpp"

namespace idk::test {
using conformance::readCube;
}  // namespace idk::test
