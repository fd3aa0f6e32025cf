#pragma once
// Chapter 08's screen-space pass in compute: AO in the narrow disk and one-bounce diffuse
// interreflection in the wide one, in one pass over the G-buffer and chapter 03's light
// buffer (shaders/ssgi.comp), then the bilateral blur when the pattern is randomised, and
// optionally a second pass that bounces the first pass's light once more. The result texture
// holds rgb: the indirect diffuse light L1_ind, a: the visibility A of the narrow disk.
//
//   Ssgi gi;
//   gi.compute(frame.gbuffer(), frame.light().diffuse(), frame.camera(), {.samples = 16});
//   glBindTextureUnit(8, gi.texture());
#include <string>
#include <vector>

#include "chapters/02_gbuffer/gbuffer.h"
#include "chapters/08_ssgi/back_faces.h"
#include "chapters/08_ssgi/gi_math.h"
#include "common/camera.h"
#include "common/gl.h"
#include "common/image.h"
#include "common/shader.h"

namespace lp::ch08 {

// How the wide disk's light is gathered: the source's samples over the disk, each sending its
// light whatever lies between (Disk), or beyond the source, along slices with a visibility
// bitmask (Therrien et al. 2023): a sample's light counts only where nearer samples of its
// slice do not hide it (Bitmask).
enum class Gather { Disk, Bitmask };
inline const std::vector<std::string> kGatherNames = {"disk", "bitmask"};

// [settings]
struct GiSettings {
  bool indirect = true;          // the wide disk: one-bounce indirect light (off: AO alone)
  bool ao = true;                // the narrow disk: chapter 07's disk AO on the ambient light
  int samples = 32;              // samples of the pattern, 1..kMaxSamples (each read in both disks)
  Pattern pattern = Pattern::Randomised;
  float ao_radius = 0.5f;        // R_ao, world units
  float gi_radius = 2.5f;        // R_gi, world units: 5 R_ao, the source's 1:5
  float max_screen_radius = 1.f;   // the wide disk: at most this fraction of the image height (its height)
  bool blur = true;              // the bilateral 5x5 blur (randomised pattern only: the others have no noise)
  float blur_depth = 0.05f, blur_normal = 0.8f;  // chapter 07's thresholds
  int bounces = 1;               // 1, or 2: a second pass that bounces direct + first bounce again
  Gather gather = Gather::Disk;  // the wide disk's gather: the source's (no visibility) or slices + bitmask
  float thickness = 0.5f;        // Gather::Bitmask: the depth each sample is taken to have, world units
  bool back_faces = false;       // Gather::Disk: also read emitters from the back-face layer (back_faces.h)
  // One part of a larger pattern (chapter 11 accumulates the parts over frames): of the
  // spiral's samples x kernel_parts points, the ones numbered kernel_part mod kernel_parts,
  // each with its share of the whole pattern's disk and the sums times kernel_parts (so the
  // parts' mean is the whole pattern's); and the randomised pattern's turn, radians, added to
  // every pixel's. The defaults: the whole pattern, unturned.
  int kernel_parts = 1, kernel_part = 0;
  float turn = 0.f;
  // Chapter 11 too: keep each pixel's transfer total, the clamp's denominator (Ssgi::transfer()),
  // so that an accumulation can clamp its sums instead of each frame's; the blur then averages
  // the light before the clamp (light x max(transfer, 1)) and the transfer with it.
  bool keep_transfer = false;
};
inline constexpr int kMaxSamples = 128;
// [/settings]

class Ssgi {
 public:
  void reload_shaders() { programs_.clear(); }
  // Reads the G-buffer (units 0..4, as the deferred frame leaves them) and L1 (`light`, chapter
  // 03's diffuse light target, which must hold only the direct light: see no_ambient.glsl), and
  // with `back` the back-face layer's emitters too (settings.back_faces, the disk gather).
  void compute(const ch02::GBuffer& gbuffer, GLuint light, const FrameCamera& camera, const GiSettings& settings,
               const BackFaceTextures* back = nullptr);
  GLuint texture() const { return result_; }
  // With keep_transfer: R32F, each pixel's transfer total after the parts' scaling (texture()'s
  // light is the light before the clamp divided by max(transfer, 1)); else 0.
  GLuint transfer() const { return transfer_result_; }
  int width() const { return width_; }
  int height() const { return height_; }
  // The result read back, rows top to bottom: 4 channels, rgb L1_ind, a A.
  ImageF read() const;
  // Samples of the pattern actually used for `samples` (the regular grid uses rings x spokes).
  static int used_samples(Pattern pattern, int samples);

 private:
  const ShaderProgram& program(const std::string& file, const ch02::GBuffer& gbuffer);
  void pass(const ch02::GBuffer& gbuffer, GLuint light, GLuint extra, const FrameCamera& camera, const GiSettings& s,
            const BackFaceTextures* back, GLuint out, GLuint transfer_out);
  void blur(const ch02::GBuffer& gbuffer, const FrameCamera& camera, const GiSettings& s, GLuint in, GLuint out,
            GLuint transfer_in, GLuint transfer_out);

  ProgramCache programs_;
  gl::Texture raw_{GL_TEXTURE_2D}, first_{GL_TEXTURE_2D}, second_{GL_TEXTURE_2D};
  gl::Texture transfer_raw_{GL_TEXTURE_2D}, transfer_first_{GL_TEXTURE_2D}, transfer_second_{GL_TEXTURE_2D};  // keep_transfer
  GLuint result_ = 0, transfer_result_ = 0;
  int transfer_width_ = 0, transfer_height_ = 0;
  int width_ = 0, height_ = 0;
};

}  // namespace lp::ch08
