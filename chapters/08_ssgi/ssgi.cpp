#include "chapters/08_ssgi/ssgi.h"

#include "common/error.h"

namespace lp::ch08 {

const ShaderProgram& Ssgi::program(const std::string& file, const ch02::GBuffer& gbuffer) {
  std::vector<std::string> defines = gbuffer.shader_defines(0);
  return programs_.get({{GL_COMPUTE_SHADER, file}}, defines);
}

int Ssgi::used_samples(Pattern pattern, int samples) {
  if (pattern != Pattern::Regular) return samples;
  const int rings = regular_rings(samples);
  return rings * (samples / rings);
}

void Ssgi::pass(const ch02::GBuffer& gbuffer, GLuint light, GLuint extra, const FrameCamera& camera,
                const GiSettings& s, const BackFaceTextures* back, GLuint out, GLuint transfer_out) {
  const ShaderProgram& p = program("08_ssgi/shaders/ssgi.comp", gbuffer);
  const int rings = regular_rings(s.samples);
  p.set("u_view", camera.view);
  p.set("u_projection", camera.projection);
  p.set("u_samples", used_samples(s.pattern, s.samples));
  p.set("u_rings", rings);
  p.set("u_spokes", s.samples / rings);
  p.set("u_pattern", int(s.pattern));
  p.set("u_ao_radius", s.ao_radius);
  p.set("u_gi_radius", s.gi_radius);
  p.set("u_max_screen_radius", s.max_screen_radius);
  p.set("u_bounce", extra ? 1 : 0);
  p.set("u_indirect_on", s.indirect ? 1 : 0);
  p.set("u_ao_on", s.ao ? 1 : 0);
  p.set("u_gather", int(s.gather));
  p.set("u_thickness", s.thickness);
  p.set("u_back_faces", back ? 1 : 0);
  p.set("u_parts", s.kernel_parts);
  p.set("u_part", s.kernel_part);
  p.set("u_turn", s.turn);
  p.set("u_keep_transfer", transfer_out ? 1 : 0);
  p.use();
  glBindTextureUnit(9, light);
  glBindTextureUnit(10, extra ? extra : light);
  // the back-face layer on units 11..14 (unused, and the front layer's stand-ins, without it)
  const BackFaceTextures none{gbuffer.layout().depth_target ? gbuffer.depth_copy() : gbuffer.depth_stencil(),
                              gbuffer.normal(), gbuffer.albedo(), light};
  const BackFaceTextures& b = back ? *back : none;
  glBindTextureUnit(11, b.depth);
  glBindTextureUnit(12, b.normal);
  glBindTextureUnit(13, b.albedo);
  glBindTextureUnit(14, b.light);
  glBindImageTexture(0, out, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
  if (transfer_out) glBindImageTexture(1, transfer_out, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
  glDispatchCompute(GLuint((width_ + 7) / 8), GLuint((height_ + 7) / 8), 1);
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  for (GLuint unit = 9; unit <= 14; ++unit) glBindTextureUnit(unit, 0);  // the light buffers are drawn into next
}

void Ssgi::blur(const ch02::GBuffer& gbuffer, const FrameCamera& camera, const GiSettings& s, GLuint in, GLuint out,
                GLuint transfer_in, GLuint transfer_out) {
  const ShaderProgram& b = program("08_ssgi/shaders/blur.comp", gbuffer);
  b.set("u_view", camera.view);
  b.set("u_depth_threshold", s.blur_depth);
  b.set("u_normal_threshold", s.blur_normal);
  b.set("u_keep_transfer", transfer_in ? 1 : 0);
  b.use();
  glBindImageTexture(0, in, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA16F);
  glBindImageTexture(1, out, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
  if (transfer_in) {
    glBindImageTexture(2, transfer_in, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32F);
    glBindImageTexture(3, transfer_out, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
  }
  glDispatchCompute(GLuint((width_ + 7) / 8), GLuint((height_ + 7) / 8), 1);
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

// [compute]
void Ssgi::compute(const ch02::GBuffer& gbuffer, GLuint light, const FrameCamera& camera, const GiSettings& s,
                   const BackFaceTextures* back) {
  if (s.samples < 1 || s.samples > kMaxSamples)
    throw Error("ssgi: samples must be between 1 and " + std::to_string(kMaxSamples) + " (got " +
                std::to_string(s.samples) + ")");
  if (!(s.ao_radius > 0.f) || !(s.gi_radius > 0.f))
    throw Error("ssgi: the AO and indirect radii must be positive (got " + std::to_string(s.ao_radius) + " and " +
                std::to_string(s.gi_radius) + ")");
  if (!(s.thickness > 0.f)) throw Error("ssgi: the bitmask's thickness must be positive (got " + std::to_string(s.thickness) + ")");
  if (s.bounces != 1 && s.bounces != 2) throw Error("ssgi: bounces must be 1 or 2 (got " + std::to_string(s.bounces) + ")");
  if (s.kernel_parts < 1 || s.kernel_part < 0 || s.kernel_part >= s.kernel_parts)
    throw Error("ssgi: kernel_part must be in [0, kernel_parts) (got part " + std::to_string(s.kernel_part) + " of " +
                std::to_string(s.kernel_parts) + ")");
  if (s.kernel_parts > 1 && (s.pattern == Pattern::Regular || s.gather != Gather::Disk))
    throw Error("ssgi: a part of the pattern (kernel_parts > 1) needs the spiral or randomised pattern and the disk gather");
  const int w = gbuffer.width(), h = gbuffer.height();
  if (w != width_ || h != height_) {
    raw_ = gl::make_texture_2d(GL_RGBA16F, w, h);
    first_ = gl::make_texture_2d(GL_RGBA16F, w, h);
    second_ = gl::make_texture_2d(GL_RGBA16F, w, h);
    width_ = w;
    height_ = h;
  }
  if (s.keep_transfer && (w != transfer_width_ || h != transfer_height_)) {
    transfer_raw_ = gl::make_texture_2d(GL_R32F, w, h);
    transfer_first_ = gl::make_texture_2d(GL_R32F, w, h);
    transfer_second_ = gl::make_texture_2d(GL_R32F, w, h);
    transfer_width_ = w;
    transfer_height_ = h;
  }
  auto kept = [&](const gl::Texture& t) { return s.keep_transfer ? t.id() : 0u; };
  const bool blurred = s.blur && s.pattern == Pattern::Randomised;
  if (!s.back_faces || !s.indirect || s.gather != Gather::Disk) back = nullptr;
  // 1. the first bounce (and the AO) from the direct light
  pass(gbuffer, light, 0, camera, s, back, blurred ? raw_.id() : first_.id(), kept(blurred ? transfer_raw_ : transfer_first_));
  if (blurred) blur(gbuffer, camera, s, raw_.id(), first_.id(), kept(transfer_raw_), kept(transfer_first_));
  result_ = first_.id();
  transfer_result_ = kept(transfer_first_);
  // 2. a second pass: the emitters now send direct + first-bounce light, so its result is the
  //    first bounce and the second together (and the same AO); the back faces send their direct
  //    light again (the layer has no first bounce of its own)
  if (s.bounces == 2) {
    pass(gbuffer, light, first_.id(), camera, s, back, blurred ? raw_.id() : second_.id(),
         kept(blurred ? transfer_raw_ : transfer_second_));
    if (blurred) blur(gbuffer, camera, s, raw_.id(), second_.id(), kept(transfer_raw_), kept(transfer_second_));
    result_ = second_.id();
    transfer_result_ = kept(transfer_second_);
  }
}
// [/compute]

ImageF Ssgi::read() const {
  ImageF img = ImageF::blank(width_, height_, 4);
  glGetTextureImage(result_, 0, GL_RGBA, GL_FLOAT, GLsizei(img.data.size() * sizeof(float)), img.data.data());
  flip_vertically(img);
  return img;
}

}  // namespace lp::ch08
