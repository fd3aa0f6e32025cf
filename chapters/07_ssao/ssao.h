#pragma once
// Chapter 07's ambient occlusion from the G-buffer, in compute shaders: the classic
// algorithm (a kernel of points in the hemisphere about the normal, each projected and
// tested against the depth buffer) and the source's 2D-disk method (samples in a fixed
// screen-space disk, each a disk of surface with Bunnell's occlusion term), then the
// bilateral blur. The AO texture holds the visibility A in [0, 1] (1: nothing occludes),
// at full, half or quarter resolution.
//
//   Ssao ao;
//   ao.compute(frame.gbuffer(), frame.camera(), {.method = AoMethod::Classic, .samples = 16});
//   glBindTextureUnit(8, ao.texture());
#include <string>
#include <vector>

#include "chapters/02_gbuffer/gbuffer.h"
#include "common/camera.h"
#include "common/gl.h"
#include "common/image.h"
#include "common/shader.h"

namespace lp::ch07 {

enum class AoMethod { Classic, Disk, Off, Gtao };
inline const std::vector<std::string> kMethodNames = {"classic", "disk", "off", "gtao"};

// [settings]
struct AoSettings {
  AoMethod method = AoMethod::Classic;
  int samples = 16;        // kernel points (classic) or disk samples (disk); 1..kMaxSamples
  float radius = 0.5f;     // R, world units: the ray length of the AO integral
  // classic
  bool noise = true;             // reflect the kernel about the 4x4 tile's vectors, per pixel (the
                                 // disk: turn its spiral by the tile's angle; GTAO: jitter its slices)
  bool energy_minimised = true;  // the spring-relaxed kernel instead of the random one
  bool blur = true;              // the bilateral 4x4 blur (every method; the source's disk has none)
  float blur_depth = 0.05f;      // a neighbour counts within 5 % of the centre's view depth ...
  float blur_normal = 0.8f;      // ... and within acos(0.8) = 37 degrees of its normal
  int scale = 1;                 // 1 full, 2 half, 4 quarter resolution
  float bias = 0.02f;            // classic: a point counts as hidden only this far (x R) behind
  // classic: the source's two radii at 1:5, the kernel again at R / 5 (twice the depth reads),
  // A the product of the two sets' visibilities: darker within R / 5 of contact, the wide
  // radius's A beyond it. Not the truth's integral for any one R (ssao.comp [classic]).
  bool two_radii = false;
  // disk: the disk's radius on the screen is R projected at the pixel, at most this fraction of
  // the image height (the screen-radius clamp for surfaces near the camera)
  float max_screen_radius = 0.25f;
  // disk: each sample's occlusion, the disk form factor (cosine-weighted, as the AO integral
  // is) or Bunnell's term as his code has it (a share of solid angle); ao_math.h
  bool bunnell_term = false;
  // The free parameters the sweep tunes against the truth (as XeGTAO tunes its RadiusMultiplier,
  // FalloffRange and FinalValuePower against its ray-traced reference); the defaults are the
  // untuned method, the source's parameters. reach: the method's own radius is reach x R (the
  // truth's R does not change); power: A is raised to it at the end; falloff (GTAO): occluders
  // fade out over the last falloff x R of the reach.
  float reach = 1.f;
  float power = 1.f;
  float falloff = 0.05f;
  // GTAO and the disk: what lies behind each depth sample, a slab this thick (x the reach) along
  // its view ray (0: nothing behind the surface the depth buffer holds, as the source and
  // XeGTAO have it). Negative: the method's own, kDiskThickness or kGtaoThickness below.
  // ssao.comp [thickness].
  float thickness = -1.f;
  // The noise tile's vectors turned about the normal by this angle (radians): chapter 11 turns
  // it every frame, so that frames accumulated over time see other directions.
  float turn = 0.f;
  // classic: the kernel made of samples x kernel_parts points, of which this frame takes every
  // kernel_parts-th from kernel_part on (every distance from the centre in each part): chapter
  // 11 takes the next part each frame, so kernel_parts frames together are the whole kernel.
  int kernel_parts = 1, kernel_part = 0;
  // The tutorial bug, for the test that catches it: the kernel turned into world space and
  // added to the view-space position.
  bool tutorial_bug = false;
};
inline constexpr int kMaxSamples = 128;
// The slabs' thicknesses, chosen on the tuning sweep's TRAINING view of the Cornell box (not the
// book's view the tests measure): the thinnest on the grid 0, R / 4, ..., R, 1.5 R, 2 R within 1 % of the
// least mean |A - truth| there (32 samples). Disk: 0.1316 with no slab, 0.1019 at R, 0.1016 at
// 1.5 R; GTAO: 0.1028, 0.0804 at 0.75 R, 0.0802 at R.
inline constexpr float kDiskThickness = 1.f, kGtaoThickness = 0.75f;
// [/settings]
// The thickness a method uses (AoSettings::thickness, its negative resolved).
inline float thickness_of(const AoSettings& s) {
  if (s.thickness >= 0.f) return s.thickness;
  return s.method == AoMethod::Disk ? kDiskThickness : s.method == AoMethod::Gtao ? kGtaoThickness : 0.f;
}

class Ssao {
 public:
  Ssao();
  void reload_shaders() { programs_.clear(); }
  // Reads the G-buffer (its textures bound on units 0..4, as the deferred frame leaves them).
  void compute(const ch02::GBuffer& gbuffer, const FrameCamera& camera, const AoSettings& settings);
  GLuint texture() const { return blurred_used_ ? blurred_.id() : raw_.id(); }  // what the ambient hook reads
  GLuint raw_texture() const { return raw_.id(); }
  int width() const { return width_; }
  int height() const { return height_; }
  // The AO texture read back, rows top to bottom (ImageF's convention), one channel.
  ImageF read() const;
  // The same at the G-buffer's size (nearest texel, as the ambient hook reads it).
  ImageF read_full(int width, int height) const;

 private:
  const ShaderProgram& program(const std::string& file, const ch02::GBuffer& gbuffer, std::vector<std::string> defines);
  void upload_kernel(const ShaderProgram& p, const AoSettings& s);

  ProgramCache programs_;
  gl::Texture raw_{GL_TEXTURE_2D}, blurred_{GL_TEXTURE_2D};
  int width_ = 0, height_ = 0;
  bool blurred_used_ = false;
  std::vector<glm::vec3> kernel_;
  int kernel_samples_ = -1;
  bool kernel_energy_ = false;
  std::vector<glm::vec3> noise_;
};

}  // namespace lp::ch07
