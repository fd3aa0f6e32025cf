#pragma once
// The ground truth for chapter 01: the same lighting model evaluated on the CPU, per pixel,
// on the exact surfaces the meshes approximate (spheres and rectangles from the scene's
// "lightpass" extras), in double-checked float. Tessellation, interpolation and 8-bit
// output are the only things the GPU image can differ by.
#include <vector>

#include "common/camera.h"
#include "common/image.h"
#include "common/scene.h"
#include "common/scene_gpu.h"

namespace lp::ch01 {

// The colour where no surface is hit, in the GPU renders and the ground truth alike.
inline constexpr glm::vec3 kBackground{0.02f, 0.02f, 0.025f};

struct GroundTruth {
  ImageF radiance;              // linear RGB, top row first
  std::vector<int> instance;    // index of the instance hit + 1, 0 for none; top row first
};

GroundTruth render_ground_truth(const Scene& scene, const Camera& camera, int width, int height,
                                const std::vector<Light>& lights);

// Which instance the GPU drew at each pixel (+1, 0 for none), top row first.
std::vector<int> render_instance_ids(const SceneGpu& scene, const FrameCamera& camera, int width, int height);

// Pixels where the exact sphere and its mesh are both seen, and their 8 neighbours too:
// there the mesh's shading can be compared with the exact one. (At the outline the
// inscribed polygon and the circle cover different pixels: geometry, not shading.)
std::vector<std::uint8_t> sphere_mask(const Scene& scene, const GroundTruth& truth, const std::vector<int>& gpu_ids);

// Error of an 8-bit sRGB render against the ground truth over `mask`, in 8-bit sRGB steps
// (what the reader sees): mean, 99th percentile and max of the per-pixel mean absolute
// channel difference.
FloatErrorStats sphere_error(const ImageRGBA8& render, const GroundTruth& truth, const std::vector<std::uint8_t>& mask);

// An 8-bit image as floats in 8-bit steps (0..255), RGB.
ImageF srgb_steps(const ImageRGBA8& image);

}  // namespace lp::ch01
