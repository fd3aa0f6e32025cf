#pragma once
// --show motion's picture and its key, and --show rejected's key, without OpenGL: each pixel's motion as colour (hue the
// direction it moved on screen, brightness its length up to a full scale in pixels a frame),
// and the wheel of directions (common/image's draw_direction_key) drawn with the same colours.
#include <array>
#include <cstdint>
#include <vector>

#include "common/image.h"

namespace lp::ch11 {

// The colour of a motion of (dx, dy) pixels a frame, dy up (GL's), full colour at full_scale.
std::array<std::uint8_t, 3> motion_colour(float dx, float dy, float full_scale);
// The picture of a motion target read back as RGBA32F (MotionStage::current(): xy = uv now - uv
// then, rows bottom first); rows top first, as PNGs are. Throws lp::Error when the data is not
// width x height x 4 floats.
ImageRGBA8 motion_picture(const std::vector<float>& motion, int width, int height, float full_scale);
// Its key: which colour is which way on screen, and how far full colour is.
DirectionKey motion_key(float full_scale);

// --show rejected's key: what red is (the pixels whose history was dropped), and what the rest of
// the picture is; in short words on a picture too narrow for them (160x90).
std::vector<LegendEntry> rejected_key();

}  // namespace lp::ch11
