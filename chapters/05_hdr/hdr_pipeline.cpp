#include "chapters/05_hdr/hdr_pipeline.h"

#include <optional>

namespace lp::ch05 {

void HdrPipeline::reload_shaders() {
  log_average_.reload_shaders();
  adaptation_.reload_shaders();
  bloom_.reload_shaders();
  tonemapper_.reload_shaders();
}

void HdrPipeline::process(GLuint radiance, int w, int h, const HdrSettings& s, GLuint output_framebuffer,
                          PassMetrics* metrics) {
  // [process]
  {
    auto t = timed(metrics, "hdr: log-average luminance");
    log_average_.compute(radiance, w, h, s.average, s.delta);
  }
  {
    auto t = timed(metrics, "hdr: eye adaptation");
    adaptation_.update(log_average_.result_buffer(), s.adaptation);
  }
  bool bloom = s.bloom != BloomMode::Off || s.view != HdrSettings::View::Final;
  if (bloom) {
    {
      auto t = timed(metrics, "hdr: bloom bright pass + reductions");
      bloom_.bright_pass(radiance, w, h, adaptation_.state_buffer(), s.bloom_chain);
    }
    auto t = timed(metrics, "hdr: bloom blur");
    bloom_.blur(s.bloom_chain);
  }
  BloomInput b;
  if (bloom) {
    b = {.mode = s.bloom == BloomMode::Off ? BloomMode::AfterTonemap : s.bloom,
         .texture = s.view == HdrSettings::View::BrightPass ? bloom_.bright_texture() : bloom_.blurred_texture(),
         .uv_scale = bloom_.uv_scale(),
         .strength = s.bloom_strength,
         .threshold = s.bloom_chain.threshold,
         .limit = s.bloom_chain.limit,
         .show_alone = s.view != HdrSettings::View::Final};
  }
  auto t = timed(metrics, "hdr: tonemap");
  tonemapper_.draw(radiance, w, h, adaptation_.state_buffer(), s.tonemap, b, output_framebuffer);
  // [/process]
}

}  // namespace lp::ch05
