#pragma once
// The neon tubes as light volumes: the chapter's default path. Each tube's capsule (a
// cylinder without caps) is drawn over chapter 02's G-buffer through chapter 03's two-pass
// stencil mask, and the pixels inside it call neon_light() once, adding the tube's diffuse
// and specular light into chapter 03's light buffer; chapter 03's composite then makes the
// image, with the scene's ordinary lights in it through chapter 03's own volumes.
//
//   ch02::GeometryPass geometry(scene_gpu);  ch03::LightVolumes volumes;  NeonVolumes neon;
//   geometry.draw(gbuffer, camera);  gbuffer.bind_textures(0);
//   ch03::SurfaceView view = ch03::surface_view(gbuffer);
//   light.begin(gbuffer.framebuffer());                    // G-buffer depth, zero stencil
//   volumes.draw_global(light, view, ambient);             // chapter 03: ambient, directional
//   volumes.draw_local(light, view, ch03::Strategy::Stencil);   // chapter 03: points, spots
//   neon.draw(tubes, light, view, how);                    // here: one capsule per tube
//   glBindFramebuffer(GL_FRAMEBUFFER, output);  volumes.composite(light, view, background);
#include <cstdint>
#include <string>
#include <vector>

#include "chapters/02_gbuffer/deferred.h"
#include "chapters/03_light_volumes/light_volumes.h"
#include "chapters/04_neon/neon_forward.h"
#include "common/gl.h"
#include "common/shader.h"

namespace lp::ch04 {

// Exact counts of the neon pass (chapter 03's 64-bit counters in the volume shader, early
// fragment tests), summed over the tubes.
struct NeonCounts {
  std::uint64_t shaded = 0;     // fragments the volume shader ran for
  std::uint64_t lit = 0;        // of those, the ones the tube added anything to
  std::uint64_t lit_open = 0;   // ... would have added anything to, were its barn doors open
  std::uint64_t marking = 0;    // fragments of the stencil-marking draws that passed the depth
                                // test (they shade nothing; GL_SAMPLES_PASSED counts them)
  std::uint64_t samples = 0;    // GL_SAMPLES_PASSED over the light draws (== shaded); 0 when
                                // drawn inside a measured pass, whose query is the active one
  double overshading() const { return lit ? double(shaded) / double(lit) : 0.0; }
};

class NeonVolumes {
 public:
  NeonVolumes();
  void reload_shaders();

  // Every tube's light added into `light` (bound here), each tube through its own stencil
  // mask (ch03::draw_stencil_volumes). `how.term` does not matter here: the light buffer
  // holds both terms; draw_term() shows one.
  // With `waste`, each tube adds a colour instead of its light (see neon_volume.frag): what
  // the capsules shade, lit or not.
  void draw(const NeonTubes& tubes, const ch03::LightBuffer& light, const ch03::SurfaceView& view, const NeonDraw& how,
            bool waste = false);

  // Counting costs atomic operations and a query per tube: on for tests and the panel. The
  // counters start each draw at `start` (0; tests start them near 2^32 to see them cross it):
  // every tube's counts are start + what was counted.
  void set_counting(bool on, std::uint64_t start = 0) {
    counting_ = on;
    count_start_ = start;
  }
  bool counting() const { return counting_; }
  const NeonCounts& counts() const { return counts_; }                    // of the last draw
  const std::vector<NeonCounts>& tube_counts() const { return per_tube_; }  // per tube

  // One term of the light buffer into the bound framebuffer, as the forward pass's --term
  // shows it: albedo x L1 (Term::Diffuse) or L2 (Term::Specular); sky pixels: background.
  void draw_term(const ch03::LightBuffer& light, const ch03::SurfaceView& view, Term term, const glm::vec3& background);

  // Pictures over the bound output, whose depth-stencil holds the G-buffer's depth and a zero
  // stencil: every capsule as a wireframe in its tube's colour, depth-tested; with `masks`,
  // first each tube's stencil mask (the pixels its light pass shades), tinted in its colour.
  void draw_pictures(const NeonTubes& tubes, const ch03::SurfaceView& view, bool masks);

 private:
  const ShaderProgram& program(const std::string& vertex, const std::string& fragment, const ch03::SurfaceView& view,
                               std::vector<std::string> extra = {});
  ProgramCache programs_;
  ch02::FullScreenPass full_screen_;
  ch03::FragmentCounters counters_;  // per tube: shaded, lit, lit_open, marking
  std::uint64_t count_start_ = 0;
  gl::Query samples_{GL_SAMPLES_PASSED};
  bool counting_ = false;
  NeonCounts counts_;
  std::vector<NeonCounts> per_tube_;
};

}  // namespace lp::ch04
