#include "chapters/03_light_volumes/light_volumes.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "common/error.h"

namespace lp::ch03 {

namespace {

constexpr int kShapeSphere = 0, kShapeCone = 1, kShapeFullScreen = 2;  // as in light_instance.glsl
constexpr GLuint kLightBufferUnit = LightBuffer::kFirstUnit;

// Depth comparisons for the G-buffer's convention: standard (near 0, far 1) or reversed-Z.
struct DepthTests {
  GLenum less, less_equal, greater;
};
DepthTests depth_tests(const SurfaceView& v) {
  return v.reversed_z ? DepthTests{GL_GREATER, GL_GEQUAL, GL_LESS} : DepthTests{GL_LESS, GL_LEQUAL, GL_GREATER};
}

void begin_depth_convention(const SurfaceView& v) {
  if (v.reversed_z) glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
}

// What every function here leaves behind: OpenGL's defaults, depth test on (as chapter 02).
void restore_state() {
  glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthMask(GL_TRUE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_DEPTH_CLAMP);
  glDisable(GL_BLEND);
  glDisable(GL_STENCIL_TEST);
  glStencilMask(0xFF);
  glStencilFunc(GL_ALWAYS, 0, 0xFF);
  glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
}

void additive_volume_state() {
  // [additive-state]
  // Every light adds to what the lights before it left; nothing here writes depth, and the
  // volumes are never clipped by the near or the far plane: depth clamp keeps them whole
  // (their depths are clamped to the planes instead), so a light crossing a plane is
  // still covered.
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  glDepthMask(GL_FALSE);
  glEnable(GL_DEPTH_CLAMP);
  // [/additive-state]
}

// [stencil-light]
// Pass 1, the mask. Both faces, no colour. Along the ray through a pixel, the surface is
// inside the volume when it lies in front of the back face (the back face fails the depth
// test: +1) but not in front of the front face (the front face fails: -1). Behind the
// volume neither fails (0), in front of it both do (0), and with the eye inside there is
// no front face: the back face alone gives 1.
// `bits`: the low stencil bits the mask counts in (all 8 here; chapter 10 counts in 0x7F and
// keeps bit 7 for its MSAA edge mark). The low 7 bits of a count wrapped up or down are the
// same whatever bit 7 holds, so they count modulo 128 alone, and the write mask keeps bit 7.
void stencil_mark_state(const DepthTests& tests, GLuint bits = 0xFF) {
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(tests.less_equal);
  glDisable(GL_CULL_FACE);
  glStencilMask(bits);
  glStencilFunc(GL_ALWAYS, 0, 0xFF);
  glStencilOpSeparate(GL_BACK, GL_KEEP, GL_INCR_WRAP, GL_KEEP);
  glStencilOpSeparate(GL_FRONT, GL_KEEP, GL_DECR_WRAP, GL_KEEP);
}

// Pass 2, the light. Back faces only, so each pixel of the volume is shaded once (also with
// the eye inside), and no depth test: the mask has done it. Where the stencil is not 0 the
// pixel is shaded and its stencil set back to 0: the next light finds a clean stencil with
// no clear at all.
void stencil_shade_state(GLuint bits = 0xFF) {
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_FRONT);
  glStencilFunc(GL_NOTEQUAL, 0, bits);
  glStencilOp(GL_KEEP, GL_KEEP, GL_ZERO);
}
// [/stencil-light]

gl::Texture make_target(GLenum format, int w, int h) {
  gl::Texture t = gl::make_texture_2d(format, w, h);
  glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  return t;
}

// A vertex array for one unit mesh and one stream of light records (divisor 1: the record
// advances once per instance, not per vertex).
void setup_vertex_array(GLuint vao, GLuint vertices, GLuint indices, GLuint instances, GLsizei stride, bool spot) {
  glVertexArrayVertexBuffer(vao, 0, vertices, 0, sizeof(glm::vec3));
  glEnableVertexArrayAttrib(vao, 0);
  glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(vao, 0, 0);
  glVertexArrayElementBuffer(vao, indices);
  // [instance-attributes]
  glVertexArrayVertexBuffer(vao, 1, instances, 0, stride);
  glVertexArrayBindingDivisor(vao, 1, 1);
  for (GLuint k = 0; k < (spot ? 3u : 2u); ++k) {
    glEnableVertexArrayAttrib(vao, 4 + k);  // i_position_radius, i_radiance_range, i_direction_cone
    glVertexArrayAttribFormat(vao, 4 + k, 4, GL_FLOAT, GL_FALSE, 16 * k);
    glVertexArrayAttribBinding(vao, 4 + k, 1);
  }
  // [/instance-attributes]
}

}  // namespace

bool is_strategy(const std::string& name) {
  return std::find(kStrategies.begin(), kStrategies.end(), name) != kStrategies.end();
}

Strategy strategy_named(const std::string& name) {
  for (std::size_t i = 0; i < kStrategies.size(); ++i)
    if (kStrategies[i] == name) return static_cast<Strategy>(i);
  throw Error("unknown light-volume strategy '" + name + "'");
}

GlobalPass global_pass_named(const std::string& name) {
  for (std::size_t i = 0; i < kGlobalPasses.size(); ++i)
    if (kGlobalPasses[i] == name) return static_cast<GlobalPass>(i);
  throw Error("unknown global pass '" + name + "' (fragment or compute)");
}

std::vector<std::string> ShaderHooks::glsl_defines() const {
  std::vector<std::string> all = {"FRAME_VISIBILITY \"" + visibility + "\"", "FRAME_AMBIENT \"" + ambient + "\""};
  all.insert(all.end(), defines.begin(), defines.end());
  return all;
}

SurfaceView surface_view(const ch02::GBuffer& gbuffer) {
  return {gbuffer.camera(), ch02::is_reversed_z(gbuffer.layout()), gbuffer.shader_defines(0)};
}

// --- The light buffer ------------------------------------------------------------------------

LightBuffer::LightBuffer(int width, int height, GLenum depth_stencil_format, Kind kind)
    : width_(width), height_(height), kind_(kind),
      diffuse_(make_target(GL_RGBA16F, width, height)),
      specular_(kind == Kind::PrePass ? gl::Texture(GL_TEXTURE_2D) : make_target(GL_RGBA16F, width, height)),
      depth_stencil_(make_target(depth_stencil_format, width, height)) {
  if (width <= 0 || height <= 0) throw Error("a light buffer needs at least one pixel");
  glNamedFramebufferTexture(fbo_.id(), GL_COLOR_ATTACHMENT0, diffuse_.id(), 0);
  if (kind == Kind::DiffuseAndSpecular) glNamedFramebufferTexture(fbo_.id(), GL_COLOR_ATTACHMENT1, specular_.id(), 0);
  const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glNamedFramebufferDrawBuffers(fbo_.id(), kind == Kind::PrePass ? 1 : 2, buffers);
  glNamedFramebufferTexture(fbo_.id(), GL_DEPTH_STENCIL_ATTACHMENT, depth_stencil_.id(), 0);
  if (glCheckNamedFramebufferStatus(fbo_.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw Error("the light buffer framebuffer (" + std::to_string(width) + "x" + std::to_string(height) + ") is incomplete");
}

std::size_t LightBuffer::bytes() const {
  std::size_t per_pixel = 8 * (kind_ == Kind::PrePass ? 1 : 2) + 4;  // RGBA16F targets + depth-stencil
  return per_pixel * std::size_t(width_) * std::size_t(height_);
}

void LightBuffer::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
  glViewport(0, 0, width_, height_);
  glDisable(GL_FRAMEBUFFER_SRGB);  // float targets: nothing to encode
}

// [begin-light-buffer]
void LightBuffer::begin(GLuint gbuffer_framebuffer) const {
  // The light shaders read the G-buffer's depth texture; attaching that same texture here
  // while the stencil is written would be a feedback loop, so the volumes test against a
  // copy. The blit needs both depth formats equal (the constructor's argument).
  glDisable(GL_SCISSOR_TEST);
  glDepthMask(GL_TRUE);
  glStencilMask(0xFF);
  glBlitNamedFramebuffer(gbuffer_framebuffer, fbo_.id(), 0, 0, width_, height_, 0, 0, width_, height_,
                         GL_DEPTH_BUFFER_BIT, GL_NEAREST);
  const GLint zero = 0;
  glClearNamedFramebufferiv(fbo_.id(), GL_STENCIL, 0, &zero);  // once a frame; each light leaves it at 0
  bind();
}
// [/begin-light-buffer]

void LightBuffer::bind_textures() const {
  glBindTextureUnit(kFirstUnit + 0, diffuse_.id());
  glBindTextureUnit(kFirstUnit + 1, specular_.id());
}

std::vector<std::string> LightBuffer::shader_defines() { return {"LIGHT_BUFFER_UNIT " + std::to_string(kFirstUnit)}; }

void LightBuffer::bind_images(GLenum access) const {
  glBindImageTexture(kFirstImage + 0, diffuse_.id(), 0, GL_FALSE, 0, access, GL_RGBA16F);
  if (kind_ == Kind::DiffuseAndSpecular) glBindImageTexture(kFirstImage + 1, specular_.id(), 0, GL_FALSE, 0, access, GL_RGBA16F);
}

std::vector<std::string> LightBuffer::image_defines() { return {"LIGHT_BUFFER_IMAGE " + std::to_string(kFirstImage)}; }

void LightBuffer::dispatch_per_pixel() const {
  glDispatchCompute(GLuint((width_ + 7) / 8), GLuint((height_ + 7) / 8), 1);
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
}

void LightBuffer::clear() const {
  const float zero[4] = {0, 0, 0, 0};
  glClearNamedFramebufferfv(fbo_.id(), GL_COLOR, 0, zero);
  if (kind_ == Kind::DiffuseAndSpecular) glClearNamedFramebufferfv(fbo_.id(), GL_COLOR, 1, zero);
}

// --- Scissor rectangles ----------------------------------------------------------------------

// [scissor-rect]
// The sphere seen from the camera (view space, looking down -z, `depth` = -z) is bounded
// left and right by the two planes through the eye tangent to it. In the x-z plane a line
// x = m depth touches the circle (cx, cz) of radius r where (cx - m cz)^2 = r^2 (1 + m^2):
//     m = (cx cz -+ r sqrt(cx^2 + cz^2 - r^2)) / (cz^2 - r^2),
// and the projection maps the slope m to x_ndc = P[0][0] m (the same for y with P[1][1]).
// The formula needs the whole sphere in front of the eye; nearer than that, we give up and
// take the whole screen (always correct, only slower).
std::optional<glm::ivec4> scissor_rect(const FrameCamera& camera, const glm::vec3& centre, float radius, int width,
                                       int height) {
  const glm::ivec4 everything(0, 0, width, height);
  const glm::vec3 c = glm::vec3(camera.view * glm::vec4(centre, 1.f));
  const float cz = -c.z;
  if (cz + radius < camera.znear) return std::nullopt;  // wholly nearer than the near plane
  if (cz - radius <= camera.znear) return everything;    // reaches the near plane
  const glm::mat4& p = camera.projection;
  if (p[2][0] != 0.f || p[2][1] != 0.f) return everything;  // an off-centre projection: not handled
  auto bounds = [&](float ca, float scale, int pixels, int& lo, int& hi) {
    const float t = std::sqrt(ca * ca + cz * cz - radius * radius), d = cz * cz - radius * radius;
    const float ndc_lo = scale * (ca * cz - radius * t) / d, ndc_hi = scale * (ca * cz + radius * t) / d;
    // One pixel more on each side absorbs float rounding.
    lo = std::max(0, int(std::floor((ndc_lo + 1.f) * 0.5f * pixels)) - 1);
    hi = std::min(pixels, int(std::ceil((ndc_hi + 1.f) * 0.5f * pixels)) + 1);
  };
  int x0, x1, y0, y1;
  bounds(c.x, p[0][0], width, x0, x1);
  bounds(c.y, p[1][1], height, y0, y1);
  if (x1 <= x0 || y1 <= y0) return std::nullopt;  // off screen
  return glm::ivec4(x0, y0, x1 - x0, y1 - y0);
}
// [/scissor-rect]

// --- The renderer ----------------------------------------------------------------------------

struct LightVolumes::Group {
  int first_light = 0;  // light order of its first light
  GLuint vao = 0;
  GLsizei index_count = 0;
  int count = 0;
  bool spot = false;
  int shape = kShapeSphere;
  const VolumeMesh* mesh = nullptr;
  float unit_bound = 1;  // sphere: distance of its vertices; cone: see bound()
  const PointInstance* points = nullptr;
  const SpotInstance* spots = nullptr;

  glm::vec4 position_radius(int i) const { return spot ? spots[i].position_radius : points[i].position_radius; }
  glm::mat4 transform(int i) const { return spot ? volume_transform(spots[i], shape == kShapeCone) : volume_transform(points[i]); }
  // A sphere around the light holding its whole volume (for a quick "camera far outside").
  float bound(int i) const {
    float r = position_radius(i).w;
    if (shape != kShapeCone) return r * unit_bound;
    float c = spots[i].direction_cone.z, tan_outer = std::sqrt(std::max(0.f, 1.f - c * c)) / c;
    return r * std::sqrt(1.f + tan_outer * tan_outer * unit_bound * unit_bound);
  }
};

LightVolumes::LightVolumes(int sphere_subdivisions, int cone_sides)
    : shapes_(make_volume_shapes(sphere_subdivisions, cone_sides)),
      sphere_vertices_(gl::make_buffer(shapes_.sphere.positions.data(), shapes_.sphere.positions.size() * sizeof(glm::vec3))),
      sphere_indices_(gl::make_buffer(shapes_.sphere.indices.data(), shapes_.sphere.indices.size() * sizeof(std::uint32_t))),
      cone_vertices_(gl::make_buffer(shapes_.cone.positions.data(), shapes_.cone.positions.size() * sizeof(glm::vec3))),
      cone_indices_(gl::make_buffer(shapes_.cone.indices.data(), shapes_.cone.indices.size() * sizeof(std::uint32_t))) {
  set_lights({});
}

void LightVolumes::reload_shaders() {
  programs_.reload();
}

const ShaderProgram& LightVolumes::program(const std::string& fragment, const SurfaceView& view, std::vector<std::string> extra,
                                           bool volumes) {
  std::vector<std::string> defines = view.defines;
  const std::vector<std::string> hooks = view.hooks.glsl_defines();
  defines.insert(defines.end(), hooks.begin(), hooks.end());
  defines.insert(defines.end(), extra.begin(), extra.end());
  const std::string vertex = volumes ? "03_light_volumes/shaders/volume.vert" : "02_gbuffer/shaders/fullscreen.vert";
  return programs_.get({{GL_VERTEX_SHADER, vertex}, {GL_FRAGMENT_SHADER, fragment}}, defines);
}

const ShaderProgram& LightVolumes::compute_program(const std::string& compute, const SurfaceView& view,
                                                   std::vector<std::string> extra) {
  std::vector<std::string> defines = view.defines;
  const std::vector<std::string> hooks = view.hooks.glsl_defines();
  defines.insert(defines.end(), hooks.begin(), hooks.end());
  defines.insert(defines.end(), extra.begin(), extra.end());
  return programs_.get({{GL_COMPUTE_SHADER, compute}}, defines);
}

void LightVolumes::set_lights(LightSet lights) {
  lights_ = std::move(lights);
  points_ = gl::make_buffer(lights_.points.data(), lights_.points.size() * sizeof(PointInstance));
  cones_ = gl::make_buffer(lights_.cones.data(), lights_.cones.size() * sizeof(SpotInstance));
  wide_spots_ = gl::make_buffer(lights_.wide_spots.data(), lights_.wide_spots.size() * sizeof(SpotInstance));
  directional_ = gl::make_buffer(lights_.directional.data(), lights_.directional.size() * sizeof(ch01::GpuLight));
  setup_vertex_array(points_vao_.id(), sphere_vertices_.id(), sphere_indices_.id(), points_.id(), sizeof(PointInstance), false);
  setup_vertex_array(cones_vao_.id(), cone_vertices_.id(), cone_indices_.id(), cones_.id(), sizeof(SpotInstance), true);
  setup_vertex_array(wide_vao_.id(), sphere_vertices_.id(), sphere_indices_.id(), wide_spots_.id(), sizeof(SpotInstance), true);
}

std::vector<LightVolumes::Group> LightVolumes::groups() const {
  const float sphere_bound = glm::length(shapes_.sphere.positions[0]);
  const float cone_corner = 1.f / std::cos(std::numbers::pi_v<float> / float(shapes_.cone_sides));
  const GLsizei sphere_indices = GLsizei(shapes_.sphere.indices.size()), cone_indices = GLsizei(shapes_.cone.indices.size());
  const int points = int(lights_.points.size()), cones = int(lights_.cones.size());
  std::vector<Group> g = {
      {0, points_vao_.id(), sphere_indices, points, false, kShapeSphere, &shapes_.sphere, sphere_bound,
       lights_.points.data(), nullptr},
      {points, cones_vao_.id(), cone_indices, cones, true, kShapeCone, &shapes_.cone, cone_corner, nullptr,
       lights_.cones.data()},
      {points + cones, wide_vao_.id(), sphere_indices, int(lights_.wide_spots.size()), true, kShapeSphere,
       &shapes_.sphere, sphere_bound, nullptr, lights_.wide_spots.data()},
  };
  std::erase_if(g, [](const Group& x) { return x.count == 0; });
  return g;
}

void LightVolumes::set_volume_uniforms(const ShaderProgram& p, const SurfaceView& view) const {
  p.set("u_view_projection", view.camera.view_projection());
}

void LightVolumes::draw_group(const Group& g, const ShaderProgram& p, int first, int count, bool full_screen) const {
  p.use();
  p.set("u_shape", full_screen ? kShapeFullScreen : g.shape);
  p.set("u_spot", int(g.spot));
  p.set("u_first_light", g.first_light + first);
  glBindVertexArray(g.vao);
  if (full_screen)
    glDrawArraysInstancedBaseInstance(GL_TRIANGLES, 0, 3, count, GLuint(first));
  else
    glDrawElementsInstancedBaseInstance(GL_TRIANGLES, g.index_count, GL_UNSIGNED_INT, nullptr, count, GLuint(first));
}

const ShaderProgram& LightVolumes::volume_program(const std::string& fragment, const SurfaceView& view,
                                                  std::vector<std::string> extra) {
  const ShaderProgram& p = program(fragment, view, std::move(extra));
  set_volume_uniforms(p, view);
  return p;
}

void LightVolumes::draw_volume(const ShaderProgram& program, int index) const {
  for (const Group& g : groups()) {
    if (index < g.count) return draw_group(g, program, index, 1, false);
    index -= g.count;
  }
  throw Error("there is no local light " + std::to_string(index) + " to draw the volume of");
}

bool LightVolumes::camera_inside(const Group& g, int i, const glm::vec3& eye) const {
  if (glm::distance(eye, glm::vec3(g.position_radius(i))) > 1.01f * g.bound(i)) return false;
  glm::vec3 local = glm::vec3(glm::inverse(g.transform(i)) * glm::vec4(eye, 1.f));
  return g.mesh->contains(local, 0.01f);  // (near the surface counts as inside: always safe)
}

void LightVolumes::draw_global(const LightBuffer& target, const SurfaceView& view, const glm::vec3& ambient, GlobalPass how) {
  std::vector<std::string> extra = {};
  if (target.kind() == LightBuffer::Kind::PrePass) extra.push_back("LIGHT_PREPASS 1");
  // Both leave the same state behind: the light buffer bound, no depth test, no blending.
  target.bind();
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_CULL_FACE);
  glDepthMask(GL_FALSE);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, directional_.id());
  if (how == GlobalPass::Fragment) {
    const ShaderProgram& p = program("03_light_volumes/shaders/global.frag", view, extra, false);
    p.use();
    p.set("u_ambient", ambient);
    p.set("u_light_count", int(lights_.directional.size()));
    full_screen_.draw();
    restore_state();
    return;
  }
  // One invocation per pixel, writing the light buffer as images.
  const std::vector<std::string> images = LightBuffer::image_defines();
  extra.insert(extra.end(), images.begin(), images.end());
  const ShaderProgram& p = compute_program("03_light_volumes/shaders/global.comp", view, extra);
  p.use();
  p.set("u_ambient", ambient);
  p.set("u_light_count", int(lights_.directional.size()));
  target.bind_images(GL_WRITE_ONLY);
  target.dispatch_per_pixel();
}

// What every strategy draws with.
struct LightVolumes::Draw {
  const LightBuffer& target;
  const SurfaceView& view;
  const ShaderProgram& shade;  // light.frag: the light at a pixel
  const ShaderProgram& mark;   // stencil.frag: no colour, for the stencil masks
  DepthTests tests;
  std::vector<Group> groups;
};

void LightVolumes::draw_local(const LightBuffer& target, const SurfaceView& view, Strategy strategy, Output output) {
  const std::vector<std::string> counting = counting_ ? FragmentCounters::defines() : std::vector<std::string>{};
  std::vector<std::string> extra = counting;
  if (output == Output::HeatShaded) extra.push_back("HEAT_SHADED 1");
  if (output == Output::HeatLit) extra.push_back("HEAT_LIT 1");
  if (target.kind() == LightBuffer::Kind::PrePass) extra.push_back("LIGHT_PREPASS 1");
  const ShaderProgram& shade = program("03_light_volumes/shaders/light.frag", view, extra);
  const ShaderProgram& mark = program("03_light_volumes/shaders/stencil.frag", view, counting);
  set_volume_uniforms(shade, view);
  set_volume_uniforms(mark, view);
  if (counting_) {
    counters_.reset(count_start_);
    counters_.bind();
  }
  stats_ = {};
  target.bind();
  begin_depth_convention(view);
  const Draw d{target, view, shade, mark, depth_tests(view), groups()};
  additive_volume_state();
  // [strategy-table]
  using StrategyDraw = void (LightVolumes::*)(const Draw&);
  static constexpr StrategyDraw kDraw[] = {&LightVolumes::draw_full_screen, &LightVolumes::draw_scissor,
                                           &LightVolumes::draw_front_faces, &LightVolumes::draw_back_faces,
                                           &LightVolumes::draw_stencil,     &LightVolumes::draw_stencil_bits};
  static_assert(std::size(kDraw) == 6, "one function per Strategy, in its order");
  (this->*kDraw[int(strategy)])(d);
  // [/strategy-table]
  restore_state();
}

void LightVolumes::draw_full_screen(const Draw& d) {
  // [full-screen]
  // One full-screen triangle per light (instanced): every pixel, every light.
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  for (const Group& g : d.groups) {
    draw_group(g, d.shade, 0, g.count, true);
    ++stats_.draw_calls;
  }
  // [/full-screen]
}

void LightVolumes::draw_scissor(const Draw& d) {
  // [scissor]
  // The full-screen triangle again, but the scissor test keeps only the rectangle
  // around the light's projected sphere: one draw per light, no depth test.
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glEnable(GL_SCISSOR_TEST);
  for (const Group& g : d.groups)
    for (int i = 0; i < g.count; ++i) {
      glm::vec4 pr = g.position_radius(i);
      auto rect = scissor_rect(d.view.camera, glm::vec3(pr), pr.w, d.target.width(), d.target.height());
      if (!rect) {
        ++stats_.lights_skipped;
        continue;
      }
      glScissor(rect->x, rect->y, rect->z, rect->w);
      draw_group(g, d.shade, i, 1, true);
      ++stats_.draw_calls;
    }
  // [/scissor]
}

void LightVolumes::draw_front_faces(const Draw& d) {
  // [front-faces]
  // Front faces with depth test LESS: the pixels whose surface lies behind the volume's
  // front. With the camera inside a volume there is no front face to draw, so such a
  // light is drawn from its back faces (the next strategy) instead. Consecutive lights
  // of one kind go in one instanced draw, in light order.
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_CULL_FACE);
  for (const Group& g : d.groups) {
    int first = 0;
    while (first < g.count) {
      const bool inside = camera_inside(g, first, d.view.camera.position);
      int end = first + 1;
      while (end < g.count && camera_inside(g, end, d.view.camera.position) == inside) ++end;
      glCullFace(inside ? GL_FRONT : GL_BACK);
      glDepthFunc(inside ? d.tests.greater : d.tests.less);
      draw_group(g, d.shade, first, end - first, false);
      ++stats_.draw_calls;
      if (inside) stats_.lights_camera_inside += end - first;
      first = end;
    }
  }
  // [/front-faces]
}

void LightVolumes::draw_back_faces(const Draw& d) {
  // [back-faces]
  // Back faces with depth test GREATER: the pixels whose surface lies in front of the
  // volume's back. Right with the camera inside; it still shades everything in front of
  // the light, and depth clamp keeps back faces beyond the far plane. One instanced
  // draw per mesh for all lights.
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_FRONT);
  glDepthFunc(d.tests.greater);
  for (const Group& g : d.groups) {
    draw_group(g, d.shade, 0, g.count, false);
    ++stats_.draw_calls;
  }
  // [/back-faces]
}

void LightVolumes::draw_stencil(const Draw& d) {
  // [stencil]
  // Per light: the mask, then the light through it.
  glEnable(GL_STENCIL_TEST);
  for (const Group& g : d.groups)
    for (int i = 0; i < g.count; ++i) {
      stencil_mark_state(d.tests);
      draw_group(g, d.mark, i, 1, false);
      stencil_shade_state();
      draw_group(g, d.shade, i, 1, false);
      stats_.draw_calls += 2;
    }
  // [/stencil]
}

void LightVolumes::draw_stencil_bits(const Draw& d) {
  // [stencil-bits]
  // The same mask, but eight lights share the stencil buffer, one bit each: eight mark
  // passes, then eight light passes. Along a pixel's ray at most the back face and the
  // front face of a convex volume fail the depth test, and the surface is inside when
  // exactly one does: inverting the light's bit on each failure leaves it set exactly
  // there. The GPU waits for the marks once per eight lights instead of once per light.
  glEnable(GL_STENCIL_TEST);
  for (const Group& g : d.groups)
    for (int first = 0; first < g.count; first += 8) {
      const int batch = std::min(8, g.count - first);
      glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
      glEnable(GL_DEPTH_TEST);
      glDepthFunc(d.tests.less_equal);
      glDisable(GL_CULL_FACE);
      glStencilFunc(GL_ALWAYS, 0, 0xFF);
      glStencilOp(GL_KEEP, GL_INVERT, GL_KEEP);
      for (int b = 0; b < batch; ++b) {
        glStencilMask(1u << b);
        draw_group(g, d.mark, first + b, 1, false);
      }
      glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
      glDisable(GL_DEPTH_TEST);
      glEnable(GL_CULL_FACE);
      glCullFace(GL_FRONT);
      glStencilOp(GL_KEEP, GL_KEEP, GL_ZERO);
      for (int b = 0; b < batch; ++b) {
        glStencilMask(1u << b);  // shade where bit b is set, and clear only bit b
        glStencilFunc(GL_NOTEQUAL, 0, 1u << b);
        draw_group(g, d.shade, first + b, 1, false);
      }
      stats_.draw_calls += 2 * batch;
    }
  // [/stencil-bits]
}

// [volume-hook]
void draw_stencil_volumes(const SurfaceView& view, int count, const std::function<void(int, VolumePass)>& draw,
                          GLuint stencil_bits) {
  begin_depth_convention(view);
  const DepthTests tests = depth_tests(view);
  additive_volume_state();
  glEnable(GL_STENCIL_TEST);
  for (int i = 0; i < count; ++i) {
    stencil_mark_state(tests, stencil_bits);
    draw(i, VolumePass::Mark);
    stencil_shade_state(stencil_bits);
    draw(i, VolumePass::Shade);
  }
  restore_state();
}
// [/volume-hook]

FragmentCounts LightVolumes::counts() const {
  const std::vector<std::uint64_t> c = counters_.read();
  return {.shaded = c[0], .lit = c[1], .lit_inner = c[2], .marking = c[3]};
}

void LightVolumes::composite(const LightBuffer& light, const SurfaceView& view, const glm::vec3& background) {
  const ShaderProgram& p = program("03_light_volumes/shaders/composite.frag", view, LightBuffer::shader_defines(), false);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_SCISSOR_TEST);
  light.bind_textures();
  p.use();
  p.set("u_background", background);
  full_screen_.draw();
  restore_state();
}

void LightVolumes::composite_compute(const LightBuffer& light, const SurfaceView& view, const glm::vec3& background,
                                     GLuint image) {
  constexpr GLuint kOutputImage = 0;  // an image unit, bound just before the dispatch (no hook reads images)
  std::vector<std::string> defines = LightBuffer::shader_defines();
  defines.push_back("COMPOSITE_IMAGE " + std::to_string(kOutputImage));
  const ShaderProgram& p = compute_program("03_light_volumes/shaders/composite.comp", view, defines);
  light.bind_textures();
  p.use();
  p.set("u_background", background);
  glBindImageTexture(kOutputImage, image, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
  light.dispatch_per_pixel();  // (the light buffer's size: the output's)
}

void LightVolumes::draw_wireframe(const SurfaceView& view) {
  const ShaderProgram& p = program("03_light_volumes/shaders/flat_colour.frag", view);
  set_volume_uniforms(p, view);
  p.set("u_alpha", 1.f);
  begin_depth_convention(view);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(depth_tests(view).less_equal);
  glDepthMask(GL_FALSE);
  glDisable(GL_CULL_FACE);
  glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
  for (const Group& g : groups()) draw_group(g, p, 0, g.count, false);
  restore_state();
}

void LightVolumes::draw_stencil_mask(const SurfaceView& view, int index) {
  const ShaderProgram& mark = program("03_light_volumes/shaders/stencil.frag", view);
  const ShaderProgram& tint = program("03_light_volumes/shaders/flat_colour.frag", view);
  set_volume_uniforms(mark, view);
  set_volume_uniforms(tint, view);
  const int asked = index;
  for (const Group& g : groups()) {
    if (index >= g.count) {
      index -= g.count;
      continue;
    }
    begin_depth_convention(view);
    glEnable(GL_DEPTH_CLAMP);
    glDepthMask(GL_FALSE);
    glEnable(GL_STENCIL_TEST);
    // The mask, exactly as draw_local's stencil strategy makes it, and the pixels it lets
    // through, tinted.
    stencil_mark_state(depth_tests(view));
    draw_group(g, mark, index, 1, false);
    stencil_shade_state();
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    tint.set("u_alpha", 0.55f);
    draw_group(g, tint, index, 1, false);
    // Its outline, over everything.
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    tint.set("u_alpha", 1.f);
    draw_group(g, tint, index, 1, false);
    restore_state();
    return;
  }
  throw Error("there is no light " + std::to_string(asked) + " to show the stencil mask of (" +
              std::to_string(lights_.local_count()) + " local lights)");
}

void LightVolumes::draw_heat(const LightBuffer& counts, float full_scale) {
  SurfaceView none;
  const ShaderProgram& p = program("03_light_volumes/shaders/heat.frag", none, {}, false);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_STENCIL_TEST);
  glBindTextureUnit(kLightBufferUnit, counts.diffuse());
  p.use();
  p.set("u_full_scale", full_scale);
  full_screen_.draw();
  restore_state();
}

void LightVolumes::draw_light_target(GLuint texture, float scale) {
  SurfaceView none;
  const ShaderProgram& p = program("03_light_volumes/shaders/show_light.frag", none, {}, false);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_STENCIL_TEST);
  glBindTextureUnit(kLightBufferUnit, texture);
  p.use();
  p.set("u_scale", scale);
  full_screen_.draw();
  restore_state();
}

}  // namespace lp::ch03
