#pragma once
// Neon lights from a glTF scene. A neon light is a node (usually without a mesh) whose local
// X axis is the tube, centred on the node's origin, with
//
//   "extras": {"lightpass": {"neon": {
//       "length": 2.0,             metres along the node's local X (required, >= 0)
//       "intensity": 1.2,          the whole tube, chapter 01's units (required, > 0)
//       "color": [1, 0.3, 0.6],    linear RGB (default white)
//       "radius": 0.03,            the glass tube (default 0.02, > 0)
//       "specular": 1.0,           scales the specular term (default 1)
//       "caps": true,              false: cylinder volume, nothing lit beyond the ends
//       "barn_doors": [distance, count, transmittance, softness]   (default: none)
//   }}}
//
// The node's local +Y is the side of the first barn door. Scale is ignored except along X.
#include <vector>

#include "chapters/04_neon/neon.h"
#include "common/scene.h"

namespace lp::ch04 {

// Every neon light of the scene, in node order. Throws Error naming the node when its
// description is malformed (a missing or negative length, a colour that is not [r, g, b], ...).
std::vector<NeonLight> neon_lights(const Scene& scene);

// One description; `world` is the node's matrix.
NeonLight parse_neon(const std::string& node, const glm::mat4& world, const std::string& lightpass_json);

}  // namespace lp::ch04
