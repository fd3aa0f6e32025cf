#include "chapters/11_temporal/temporal_frame.h"

#include "common/error.h"
#include "common/target.h"

namespace lp::ch11 {

TemporalFrame::TemporalFrame(const SceneGpu& scene)
    : whole_(scene), motion_(scene), taa_(motion_), gi_(motion_), shadows_([this] { return whole_.shadow_stage(); }, motion_) {
  // After chapter 10's own stages: the motion before the lights, the sun's accumulated visibility
  // after it, TAA after the glass; the accumulation of AO and indirect light inside chapter 08's
  // stage, before its result is added to the light.
  whole_.add_stage(motion_);
  whole_.add_stage(shadows_);
  whole_.add_stage(taa_);
  whole_.set_gi_filter(&gi_);
}

void TemporalFrame::reload_shaders() {
  whole_.reload_shaders();
  motion_.reload_shaders();
  taa_.reload_shaders();
  gi_.reload_shaders();
  shadows_.reload_shaders();
}

// [temporal-render]
void TemporalFrame::render(const FrameCamera& camera, const ch03::FrameOutput& output, const TemporalSettings& s,
                           float dt, bool cut, PassMetrics* metrics) {
  const bool new_shot = cut || !sequence_;
  const bool taa = s.taa.enabled;
  jitter_ = taa || s.jitter_alone ? jitter_offset(index_, s.jitter_period) : glm::vec2(0);
  motion_.set_enabled(taa || s.motion_alone || s.gi.enabled || (s.pcss && s.shadows.enabled));
  motion_.set_cameras(camera, new_shot ? camera : previous_);
  if (new_shot) {
    taa_.reset();
    gi_.reset();
    shadows_.reset();
    gi_index_ = 0;
  }
  // Chapter 08's pass: this frame's part of the pattern, accumulated (temporal_gi.h); with PCSS,
  // chapter 06's disk the same way (temporal_shadows.h).
  ch10::WholeFrameSettings whole = s.whole;
  whole.gi = frame_gi(s.whole.gi, s.gi, gi_index_);
  if (s.pcss) whole.sun_shadow = frame_shadows(pcss_settings(s), s.shadows, gi_index_);
  ++gi_index_;
  gi_.set(s.gi);
  shadows_.set(s.shadows);
  // The blend's weights use the exposure chapter 05's eye last tonemapped with.
  taa_.set(s.taa, whole_.radiance() ? whole_.hdr().adaptation().state_buffer() : 0);
  taa_.set_jitter(jitter_);
  whole_.render(jittered(camera, jitter_, output.width, output.height), output, whole, dt, new_shot, metrics);
  previous_ = camera;
  sequence_ = true;
  ++index_;
}
// [/temporal-render]

void TemporalFrame::render_still(const FrameCamera& camera, glm::vec2 offset, const ch03::FrameOutput& output,
                                 const TemporalSettings& s) {
  TemporalSettings still = s;
  still.taa.enabled = false;
  motion_.set_enabled(false);
  taa_.set(still.taa, 0);
  gi_.set({});  // chapter 08's pass with its own samples, nothing accumulated
  if (still.pcss) still.whole.sun_shadow = pcss_settings(s);  // PCSS with every tap, in the hook
  jitter_ = offset;
  whole_.render(jittered(camera, offset, output.width, output.height), output, still.whole, 1.f / 30.f, true);
  sequence_ = false;
}

ch06::ShadowSettings pcss_settings(const TemporalSettings& s) {
  return {.method = ch06::ShadowMethod::Pcss, .poisson_taps = s.pcss_taps, .cascades = s.whole.sun_cascades};
}

ImageF read_linear(GLuint framebuffer, int width, int height) {
  const ImageRGBA8 image = read_framebuffer(framebuffer, width, height);
  ImageF out = ImageF::blank(width, height, 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = srgb_to_linear(image.at(x, y)[c] / 255.f);
  return out;
}

ImageF supersampled(TemporalFrame& frame, const FrameCamera& camera, int width, int height, const TemporalSettings& s,
                    int grid) {
  if (grid < 1 || grid > 16) throw Error("supersampled: a grid of " + std::to_string(grid) + " (1 to 16 a side)");
  OutputTarget target(width, height);
  ImageF sum = ImageF::blank(width, height, 3);
  for (int j = 0; j < grid; ++j)
    for (int i = 0; i < grid; ++i) {
      const glm::vec2 offset((float(i) + 0.5f) / float(grid) - 0.5f, (float(j) + 0.5f) / float(grid) - 0.5f);
      frame.render_still(camera, offset, {target.framebuffer(), width, height}, s);
      const ImageF one = read_linear(target.framebuffer(), width, height);
      for (std::size_t k = 0; k < sum.data.size(); ++k) sum.data[k] += one.data[k];
    }
  for (float& v : sum.data) v /= float(grid * grid);
  return sum;
}

}  // namespace lp::ch11
