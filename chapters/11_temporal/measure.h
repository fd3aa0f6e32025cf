#pragma once
// Measuring a temporal frame along a camera path against its supersampled truth: each
// frame's error overall and on edges, ghosting (error where the surface was hidden a few
// frames ago) and flicker (change from the last frame where the truth did not change).
// Errors are mean absolute differences of sRGB-encoded values in [0, 1] (display values: an
// 8-bit step is 1/255), over RGB.
#include <cstdint>
#include <string>
#include <vector>

#include "chapters/07_ssao/ssao.h"
#include "chapters/11_temporal/camera_path.h"
#include "chapters/11_temporal/temporal_ao.h"
#include "chapters/11_temporal/temporal_gi.h"
#include "chapters/11_temporal/temporal_shadows.h"
#include "chapters/11_temporal/temporal_frame.h"
#include "common/image.h"

namespace lp::ch11 {

// A texture's level 0 as floats, rows top first (RGBA32F motion, RGBA16F radiance: 4 channels).
ImageF read_texture_rgba(GLuint texture, int width, int height);
// Linear RGB to sRGB-encoded RGB, each channel in [0, 1].
ImageF encode_srgb(const ImageF& linear);

// [disocclusion-twin]
// The C++ twin of taa_resolve.frag's disocclusion test, on motion targets read back (motion.h):
// 1 where none of the four last-frame depths around where the pixel's surface was lies within
// `tolerance` (relative) of the depth it had there, plus `slope` pixels of the depth's change
// along the surface (the smaller one-sided difference per axis), or where it was outside the
// last image.
// `margin`, when given: per pixel, how far the nearest depth lies from the threshold, relative
// to the depth (negative: kept; infinite where outside the last image).
std::vector<std::uint8_t> disocclusion_mask(const ImageF& motion_now, const ImageF& motion_then, float tolerance,
                                            float slope = 1.5f, std::vector<float>* margin = nullptr);
// [/disocclusion-twin]

// 1 where the 3x3 neighbourhood of the (sRGB-encoded) truth spans more than `range` in luma:
// the pixels where aliasing shows.
std::vector<std::uint8_t> edge_mask(const ImageF& truth_srgb, float range = 0.1f);

// Mean absolute error of `image` against `truth` over `mask` (empty: every pixel); 0 for an
// empty selection, with `pixels` saying how many were counted.
double mean_error(const ImageF& image, const ImageF& truth, const std::vector<std::uint8_t>& mask = {},
                  std::size_t* pixels = nullptr);

// One frame of a path, measured.
struct PathFrame {
  int frame = 0;
  bool cut = false;
  double error = 0, edge_error = 0, ghost_error = 0, flicker = 0;
  std::size_t edge_pixels = 0, ghost_pixels = 0, still_pixels = 0;
  // Convergence: error and pixel count on the pixels disoccluded exactly k frames ago, k = 0 ..
  // ghost_frames * 2 - 1 (0: this frame).
  std::vector<double> since_error;
  std::vector<std::size_t> since_pixels;
};

struct PathRunOptions {
  int width = 160, height = 90;
  int first = 0, count = -1;  // the path's frames [first, first + count); -1: to the end
  int ghost_frames = 4;       // a pixel counts for ghosting this many frames after its disocclusion
  float disocclusion_tolerance = 0.05f;
  float disocclusion_slope = 1.5f;  // TaaSettings::depth_slope's
  float still_change = 1.f / 255.f;  // flicker: pixels whose truth changed less than this
  int truth_grid = 4;
  std::string dump_prefix;  // non-empty: each measured frame and its truth written as <prefix>NNN_{image,truth}.png
  // Non-null: the truths by frame, filled on first use and reused by the next variant (the
  // truth does not depend on the variant, and it is 16 frames of each measured one).
  std::vector<ImageF>* truths = nullptr;
  // Non-empty: the truths also kept as <truth_dir>/truth_<scene>_<path>_<w>x<h>_grid<g>_NNN.pfm
  // and read back when there (repeated runs of one path; the caller clears it when the scene's
  // content or the frame's settings change).
  std::string truth_dir;
};

// Plays `path` with `settings` from its frame 0 (the frames before `first` drawn, not
// measured) and measures each frame against its supersampled truth (settings without TAA,
// 16 jittered frames). The truth's frames are drawn by a second TemporalFrame, so the
// measured one's history is never disturbed.
std::vector<PathFrame> measure_path(const SceneGpu& scene, const CameraPath& path, const TemporalSettings& settings,
                                    const PathRunOptions& options);

// [ao-path]
// Chapter 07's AO along a path against its ray-traced truth (chapter 07's, cached), frame by
// frame: `ao` each frame (with temporal.enabled, its noise turned by ao_turn(frame) and
// accumulated; without, the frame's own), measured on chapter 03's frame with the AO shown.
struct AoPathFrame {
  int frame = 0;
  double error = 0;  // mean |A - truth| over the pixels that see a surface
  ImageF ao;         // A, one channel, rows top first
  // The same on the pixels disoccluded exactly k frames ago (k = 0 .. bins - 1), and how many.
  std::vector<double> since_error;
  std::vector<std::size_t> since_pixels;
};
struct AoPathOptions {
  int width = 160, height = 90;
  int first = 0, count = -1;  // the path's frames measured, as PathRunOptions'
  int truth_samples = 256;    // rays a pixel of the truth (its standard error <= 0.5 / sqrt of it)
  int bins = 8;
};
std::vector<AoPathFrame> measure_ao_path(const SceneGpu& scene, const CameraPath& path, const ch07::AoSettings& ao,
                                         const TemporalAoSettings& temporal, const AoPathOptions& options);
// [/ao-path]

// [gi-path]
// Chapter 08's pass along a path, frame by frame, on chapter 03's frame with the scene's lights:
// `gi` each frame (with temporal.enabled, frame_gi's part of the pattern, accumulated; without,
// the frame's own), its indirect light against the ray-traced truth (chapter 08's, cached; the
// screen-limited one with `screen_limited`: what a screen-space pass can know) and its AO
// against chapter 07's.
struct GiPathFrame {
  int frame = 0;
  double error = 0;     // mean |L1_ind - truth| over rgb and the pixels that see a surface
  double ao_error = 0;  // mean |A - truth| (0 without options.ao_truth)
  ImageF gi;            // the pass's result, rgb L1_ind, a A, rows top first
  ImageF transfer;      // with GiSettings::keep_transfer, this frame's transfer totals (1 channel), else empty
  std::vector<double> since_error;  // the indirect light's, on the pixels disoccluded exactly k frames ago
  std::vector<std::size_t> since_pixels;
};
struct GiPathOptions {
  int width = 160, height = 90;
  int first = 0, count = -1;  // the path's frames measured, as PathRunOptions'
  int truth_samples = 256;     // 0: no truth (the results alone, no errors)
  bool screen_limited = true;
  bool ao_truth = false;
  int bins = 8;
};
std::vector<GiPathFrame> measure_gi_path(const SceneGpu& scene, const CameraPath& path, const ch08::GiSettings& gi,
                                         const TemporalGiSettings& temporal, const GiPathOptions& options);
// [/gi-path]

// [shadow-path]
// Chapter 06's sun visibility along a path, frame by frame, on chapter 03's frame: `shadows`
// each frame (frame_shadows: with temporal.enabled, a part of PCSS's disk, accumulated; without,
// the frame's own taps), computed by the TemporalShadowStage, against chapter 06's ray-traced
// soft visibility (cached).
struct ShadowPathFrame {
  int frame = 0;
  double error = 0;   // mean |V - truth| over the pixels the sun reaches (the truth's mask)
  ImageF visibility;  // V, one channel, rows top first
  ImageF radius;      // this frame's PCSS penumbra radius (0: its search found no blocker)
  std::vector<double> since_error;  // on the pixels disoccluded exactly k frames ago
  std::vector<std::size_t> since_pixels;
};
struct ShadowPathOptions {
  int width = 160, height = 90;
  int first = 0, count = -1;  // the path's frames measured, as PathRunOptions'
  int truth_samples = 64;     // rays a pixel of the truth (0: no truth, the results alone)
  int bins = 8;
};
std::vector<ShadowPathFrame> measure_shadow_path(const SceneGpu& scene, const CameraPath& path,
                                                 const ch06::ShadowSettings& shadows,
                                                 const TemporalShadowSettings& temporal, const ShadowPathOptions& options);
// [/shadow-path]

}  // namespace lp::ch11
