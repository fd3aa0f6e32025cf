#include "chapters/04_neon/neon_volumes.h"

#include "common/metrics.h"

namespace lp::ch04 {

namespace {

constexpr int kCountersPerTube = 4;  // shaded, lit, lit_open (neon_volume.frag), marking (stencil.frag)

const char* const kCapsule = "04_neon/shaders/capsule.vert";

}  // namespace

NeonVolumes::NeonVolumes() = default;

void NeonVolumes::reload_shaders() {
  programs_.reload();
}

const ShaderProgram& NeonVolumes::program(const std::string& vertex, const std::string& fragment,
                                          const ch03::SurfaceView& view, std::vector<std::string> extra) {
  std::vector<std::string> defines = view.defines;
  defines.insert(defines.end(), extra.begin(), extra.end());
  return programs_.get({{GL_VERTEX_SHADER, vertex}, {GL_FRAGMENT_SHADER, fragment}}, defines);
}

void NeonVolumes::draw(const NeonTubes& tubes, const ch03::LightBuffer& light, const ch03::SurfaceView& view,
                       const NeonDraw& how, bool waste) {
  counts_ = {};
  per_tube_.assign(std::size_t(tubes.count()), {});
  if (tubes.count() == 0) return;
  const std::vector<std::string> counting = counting_ ? ch03::FragmentCounters::defines() : std::vector<std::string>{};
  std::vector<std::string> extra = counting;
  if (waste) extra.push_back("SHOW_WASTE 1");
  // [neon-programs]
  // The mask: the capsule placed by capsule.vert, chapter 03's empty stencil shader. The
  // light: the same capsule, and a fragment shader that lights the G-buffer's surface with
  // neon_light() (shaders/neon_volume.frag).
  const ShaderProgram& mark = program(kCapsule, "03_light_volumes/shaders/stencil.frag", view, counting);
  const ShaderProgram& shade = program(kCapsule, "04_neon/shaders/neon_volume.frag", view, extra);
  for (const ShaderProgram* p : {&mark, &shade}) {
    p->use();
    p->set("u_view_projection", view.camera.view_projection());
    p->set("u_glass", 0);  // the light's volume, not the glass
  }
  shade.set("u_method", static_cast<int>(how.method));
  shade.set("u_samples", how.samples);
  // [/neon-programs]
  if (counting_) {
    counters_.resize(kCountersPerTube * tubes.count());
    counters_.reset(count_start_);
    counters_.bind();
  }
  // A second, independent count: GL_SAMPLES_PASSED around each light pass. Only one such
  // query can be active, and a measured pass (PassMetrics) already runs one: then this one
  // is left out (samples stay 0).
  GLint outer_query = 0;
  glGetQueryiv(GL_SAMPLES_PASSED, GL_CURRENT_QUERY, &outer_query);
  const bool query = counting_ && outer_query == 0;
  light.bind();
  // [neon-volumes]
  // Chapter 03's stencil strategy, with a capsule for the volume: per tube, the mask (both
  // faces, no colour), then the light (back faces, where the mask is set).
  ch03::draw_stencil_volumes(view, tubes.count(), [&](int i, ch03::VolumePass pass) {
    const ShaderProgram& p = pass == ch03::VolumePass::Mark ? mark : shade;
    p.use();
    if (counting_) p.set("u_counter_base", kCountersPerTube * i);  // this tube's counters
    if (pass == ch03::VolumePass::Mark) {
      tubes.draw_capsule(i);
      return;
    }
    if (query) glBeginQuery(GL_SAMPLES_PASSED, samples_.id());
    tubes.draw_capsule(i);
    if (query) {
      glEndQuery(GL_SAMPLES_PASSED);
      per_tube_[std::size_t(i)].samples = query_result_u64(samples_.id());  // 64-bit (common/metrics.h)
    }
  });
  // [/neon-volumes]
  if (counting_) {
    const std::vector<std::uint64_t> c = counters_.read();
    for (int i = 0; i < tubes.count(); ++i) {
      NeonCounts& t = per_tube_[std::size_t(i)];
      const std::size_t k = std::size_t(kCountersPerTube) * std::size_t(i);
      t.shaded = c[k];
      t.lit = c[k + 1];
      t.lit_open = c[k + 2];
      t.marking = c[k + 3];
      counts_.shaded += t.shaded;
      counts_.lit += t.lit;
      counts_.lit_open += t.lit_open;
      counts_.marking += t.marking;
      counts_.samples += t.samples;
    }
  }
}

void NeonVolumes::draw_term(const ch03::LightBuffer& light, const ch03::SurfaceView& view, Term term,
                            const glm::vec3& background) {
  const ShaderProgram& p = program("02_gbuffer/shaders/fullscreen.vert", "04_neon/shaders/neon_term.frag", view,
                                   ch03::LightBuffer::shader_defines());
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glDisable(GL_STENCIL_TEST);
  light.bind_textures();
  p.use();
  p.set("u_background", background);
  p.set("u_term", static_cast<int>(term));
  full_screen_.draw();
  glEnable(GL_DEPTH_TEST);
}

void NeonVolumes::draw_pictures(const NeonTubes& tubes, const ch03::SurfaceView& view, bool masks) {
  const ShaderProgram& mark = program(kCapsule, "03_light_volumes/shaders/stencil.frag", view);
  const ShaderProgram& tint = program(kCapsule, "04_neon/shaders/mask_tint.frag", view);
  const ShaderProgram& outline = program(kCapsule, "04_neon/shaders/glass.frag", view);
  for (const ShaderProgram* p : {&mark, &tint, &outline}) {
    p->use();
    p->set("u_view_projection", view.camera.view_projection());
    p->set("u_glass", 0);
  }
  if (masks) {
    // The masks exactly as draw() makes them; the light pass adds the tube's colour instead.
    ch03::draw_stencil_volumes(view, tubes.count(), [&](int i, ch03::VolumePass pass) {
      (pass == ch03::VolumePass::Mark ? mark : tint).use();
      tubes.draw_capsule(i);
    });
  }
  // The outlines, depth-tested against the scene (the G-buffer's depth convention).
  if (view.reversed_z) glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(view.reversed_z ? GL_GEQUAL : GL_LEQUAL);
  glDepthMask(GL_FALSE);
  glDisable(GL_CULL_FACE);
  glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
  outline.use();
  tubes.draw_capsules();
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
}

}  // namespace lp::ch04
