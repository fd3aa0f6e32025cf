#pragma once
// Depth as the G-buffer stores it, and the position recovered from it, on the CPU: the
// projections for standard and reversed-Z depth, what each depth format keeps of a depth
// value, and the reconstruction with the inverse view-projection that gbuffer.glsl does.
// The unit tests measure the error of each format with these; the GPU tests check that the
// GPU agrees.
#include <glm/glm.hpp>

#include "chapters/02_gbuffer/layout.h"
#include "common/camera.h"

namespace lp::ch02 {

// [reversed-projection]
// The camera's projection for a depth format. Standard: OpenGL's, clip z in [-w, w], window
// depth (z/w + 1) / 2, so the near plane gets 0 and the far plane 1. Reversed-Z (with
// glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE)): window depth = clip z / w directly, 1 at the
// near plane and 0 at the far plane. Only the z row changes, so x, y and w (and with them
// which pixels a triangle covers) are bit-for-bit those of the standard projection:
//   depth(d) = n (f - d) / ((f - n) d)   for a point at distance d along the view axis.
glm::mat4 projection_for(DepthFormat format, const FrameCamera& camera);
// [/reversed-projection]

// The FrameCamera a G-buffer of this format is drawn with (projection replaced).
FrameCamera camera_for(DepthFormat format, const FrameCamera& camera);

// Window depth of a world point, in float, as the rasterizer computes it.
float window_depth(DepthFormat format, const glm::mat4& view_projection, const glm::vec3& world);

// What the depth buffer keeps of a window depth: 24-bit fixed point (rounded to the nearest
// of 2^24 - 1 steps) or a float32.
float stored_depth(DepthFormat format, float window_depth);

// [reconstruct-cpu]
// The world position under a pixel from its stored depth: back from window depth to
// normalised device coordinates, through the inverse view-projection, divide by w.
// ndc_xy is the pixel centre in [-1, 1]^2.
glm::vec3 reconstruct_position(DepthFormat format, const glm::mat4& inverse_view_projection, const glm::vec2& ndc_xy,
                               float depth);
// [/reconstruct-cpu]

// The inverse of a view-projection computed in double precision, rounded once to float.
glm::mat4 precise_inverse(const glm::mat4& m);

// d(window depth)/d(distance) at distance d: how much depth one metre buys there.
double depth_slope(DepthFormat format, double near, double far, double distance);

// The stated bound on |reconstructed - true position| (metres) for a point `range` metres
// from the camera (`axial` along its view axis), `magnitude` metres from the world origin.
// Derived in depth.cpp; tests/unit/test_02_encoding.cpp holds the reconstruction to it.
double reconstruction_error_bound(DepthFormat format, double near, double far, double axial, double range,
                                  double magnitude);

}  // namespace lp::ch02
