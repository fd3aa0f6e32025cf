#pragma once
// Scenes with as many lights as a measurement asks for.
#include <vector>

#include "common/scene.h"

namespace lp::ch03 {

// count <= 0: the scene's lights. Otherwise its directional lights and exactly `count` local
// lights: the scene's own first, then more of the same kind: extra light k copies colour,
// intensity and range from the scene's point lights in turn and stands at a deterministic
// random place in the box that holds them (the street's lamps stay in the street). A scene
// without point lights gets chapter 01's extra lights.
std::vector<Light> lights_for_count(const Scene& scene, int count);

}  // namespace lp::ch03
