#include "chapters/07_ssao/ssao.h"

#include <algorithm>
#include <cmath>

#include "chapters/07_ssao/ao_math.h"
#include "common/error.h"

namespace lp::ch07 {

namespace {
constexpr std::uint64_t kKernelSeed = 0x5541u, kNoiseSeed = 0x4e4fu;
}

Ssao::Ssao() : noise_(noise_tile(kNoiseSeed)) {}

const ShaderProgram& Ssao::program(const std::string& file, const ch02::GBuffer& gbuffer, std::vector<std::string> defines) {
  std::vector<std::string> all = gbuffer.shader_defines(0);
  all.insert(all.end(), defines.begin(), defines.end());
  return programs_.get({{GL_COMPUTE_SHADER, file}}, all);
}

void Ssao::upload_kernel(const ShaderProgram& p, const AoSettings& s) {
  const int all = s.samples * s.kernel_parts;
  if (kernel_samples_ != all || kernel_energy_ != s.energy_minimised) {
    kernel_ = s.energy_minimised ? energy_minimised_kernel(all, kKernelSeed) : random_kernel(all, kKernelSeed);
    kernel_samples_ = all;
    kernel_energy_ = s.energy_minimised;
  }
  std::vector<glm::vec4> k(std::size_t(s.samples)), n(noise_.size());
  for (std::size_t i = 0; i < k.size(); ++i) k[i] = glm::vec4(kernel_[i * std::size_t(s.kernel_parts) + std::size_t(s.kernel_part)], 0.f);
  const float c = std::cos(s.turn), t = std::sin(s.turn);  // the tile's vectors lie in the tangent plane (z = 0)
  for (std::size_t i = 0; i < n.size(); ++i)
    n[i] = glm::vec4(c * noise_[i].x - t * noise_[i].y, t * noise_[i].x + c * noise_[i].y, noise_[i].z, 0.f);
  glProgramUniform4fv(p.id(), p.location("u_kernel[0]"), GLsizei(k.size()), &k[0].x);
  glProgramUniform4fv(p.id(), p.location("u_noise[0]"), GLsizei(n.size()), &n[0].x);
}

// [compute]
void Ssao::compute(const ch02::GBuffer& gbuffer, const FrameCamera& camera, const AoSettings& s) {
  if (s.samples < 1 || s.samples > kMaxSamples)
    throw Error("ssao: samples must be between 1 and " + std::to_string(kMaxSamples) + " (got " +
                std::to_string(s.samples) + ")");
  if (!(s.reach > 0.f) || !(s.power > 0.f) || !(s.falloff > 0.f) || s.falloff > 1.f || std::isnan(s.thickness))
    throw Error("ssao: reach and power must be positive, falloff in (0, 1] and thickness a number");
  if (s.kernel_parts < 1 || s.kernel_parts > kMaxSamples || s.kernel_part < 0 || s.kernel_part >= s.kernel_parts ||
      s.samples * s.kernel_parts > 4 * kMaxSamples)
    throw Error("ssao: kernel_part must be in [0, kernel_parts) and samples x kernel_parts at most " +
                std::to_string(4 * kMaxSamples) + " (got part " + std::to_string(s.kernel_part) + " of " +
                std::to_string(s.kernel_parts) + ")");
  if (!(s.radius > 0.f)) throw Error("ssao: the radius must be positive (got " + std::to_string(s.radius) + ")");
  if (s.scale != 1 && s.scale != 2 && s.scale != 4) throw Error("ssao: scale must be 1, 2 or 4");
  const int w = (gbuffer.width() + s.scale - 1) / s.scale, h = (gbuffer.height() + s.scale - 1) / s.scale;
  if (w != width_ || h != height_) {
    raw_ = gl::make_texture_2d(GL_R32F, w, h);
    blurred_ = gl::make_texture_2d(GL_R32F, w, h);
    width_ = w;
    height_ = h;
  }
  const bool disk = s.method == AoMethod::Disk, gtao = s.method == AoMethod::Gtao;
  const ShaderProgram& p = program("07_ssao/shaders/ssao.comp", gbuffer,
                                   {disk ? "AO_DISK 1" : gtao ? "AO_GTAO 1" : "AO_CLASSIC 1", s.tutorial_bug ? "AO_TUTORIAL_BUG 1" : "AO_NO_BUG 1",
                                    disk && s.bunnell_term ? "AO_BUNNELL 1" : "AO_FORM_FACTOR 1"});
  upload_kernel(p, s);  // the kernel (classic) and the noise tile (every method)
  p.set("u_view", camera.view);
  p.set("u_projection", camera.projection);
  p.set("u_samples", s.samples);
  p.set("u_radius", s.radius * s.reach);
  p.set("u_power", s.power);
  p.set("u_falloff", s.falloff);
  p.set("u_thickness", thickness_of(s));
  p.set("u_scale", s.scale);
  p.set("u_noise_on", s.noise ? 1 : 0);
  p.set("u_bias", s.bias);
  p.set("u_two_radii", s.two_radii ? 1 : 0);
  p.set("u_max_screen_radius", s.max_screen_radius);
  p.use();
  glBindImageTexture(0, raw_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
  glDispatchCompute(GLuint((w + 7) / 8), GLuint((h + 7) / 8), 1);
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);

  // The blur: the classic algorithm's noise tile is 4x4, so a 4x4 box removes it where the
  // neighbours are the same surface.
  blurred_used_ = s.blur;
  if (blurred_used_) {
    const ShaderProgram& b = program("07_ssao/shaders/blur.comp", gbuffer, {});
    b.set("u_view", camera.view);
    b.set("u_scale", s.scale);
    b.set("u_depth_threshold", s.blur_depth);
    b.set("u_normal_threshold", s.blur_normal);
    b.use();
    glBindImageTexture(0, raw_.id(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32F);
    glBindImageTexture(1, blurred_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    glDispatchCompute(GLuint((w + 7) / 8), GLuint((h + 7) / 8), 1);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  }
}
// [/compute]

ImageF Ssao::read() const {
  ImageF img = ImageF::blank(width_, height_, 1);
  glGetTextureImage(texture(), 0, GL_RED, GL_FLOAT, GLsizei(img.data.size() * sizeof(float)), img.data.data());
  flip_vertically(img);
  return img;
}

ImageF Ssao::read_full(int width, int height) const {
  ImageF small = read();
  ImageF img = ImageF::blank(width, height, 1);
  // the hook's texel: pixel * size / full size, in OpenGL's rows (bottom up)
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      int gy = height - 1 - y;
      int sx = std::min(x * width_ / width, width_ - 1), sgy = std::min(gy * height_ / height, height_ - 1);
      img.at(x, y, 0) = small.at(sx, height_ - 1 - sgy, 0);
    }
  return img;
}

}  // namespace lp::ch07
