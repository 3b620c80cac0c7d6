// default_scene.hpp: the Cornell box compiled into the binary (scenes/cornell_box.gltf), so `idk render`
// and `make run` work from any directory.
#pragma once
#include "scene/scene.hpp"

namespace idk::app {

scene::Scene loadDefaultScene();

}  // namespace idk::app
