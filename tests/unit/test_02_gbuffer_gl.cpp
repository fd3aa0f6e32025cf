// Chapter 02 on the GPU (llvmpipe in CI): the G-buffer against chapter 01's forward image,
// the GLSL encoders against their C++ twins' bounds, the sky, far and grazing surfaces, a
// mesh without tangents or UVs, and the state the passes leave behind. Bounds hold on any
// conforming renderer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include <glm/gtc/matrix_transform.hpp>

#include "chapters/01_forward/blinn_phong.h"
#include "chapters/01_forward/forward.h"
#include "chapters/01_forward/ground_truth.h"
#include "chapters/02_gbuffer/deferred.h"
#include "chapters/02_gbuffer/depth.h"
#include "chapters/02_gbuffer/encoding.h"
#include "chapters/02_gbuffer/probe.h"
#include "common/metrics.h"
#include "common/paths.h"
#include "common/target.h"
#include "tests/unit/book_data.h"
#include "tests/unit/gl_environment.h"

using namespace lp;
using namespace lp::ch02;
using lp::test::book_row;

namespace {

constexpr int kW = 320, kH = 180;

double angle(const glm::dvec3& a, const glm::dvec3& b) { return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)); }

// One loaded scene with everything needed to draw it both ways.
struct World {
  explicit World(const std::string& file) : scene(load_scene(from_root(file))), gpu(scene), forward(gpu), geometry(gpu) {
    lights.upload(scene.lights);
  }
  explicit World(Scene s) : scene(std::move(s)), gpu(scene), forward(gpu), geometry(gpu) { lights.upload(scene.lights); }

  FrameCamera camera(const std::string& view, int w = kW, int h = kH) const {
    return frame_camera(scene.camera(view), float(w) / h);
  }

  ImageRGBA8 forward_image(const FrameCamera& camera, int w = kW, int h = kH) {
    OutputTarget target(w, h);
    target.bind();
    glClearColor(ch01::kBackground.r, ch01::kBackground.g, ch01::kBackground.b, 1.f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    forward.draw(camera, ch01::ForwardMode::PerPixel, lights);
    return target.read();
  }

  ImageRGBA8 deferred_image(const FrameCamera& camera, const Layout& layout, int w = kW, int h = kH) {
    GBuffer gbuffer(w, h, layout);
    geometry.draw(gbuffer, camera);
    OutputTarget target(w, h);
    target.bind();
    lighting.draw(gbuffer, lights, scene.ambient, ch01::kBackground);
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    return target.read();
  }

  // The lit deferred image in float (no sRGB, no clamping): for NaN and sky checks.
  ImageF deferred_linear(const FrameCamera& camera, const Layout& layout, int w = kW, int h = kH) {
    GBuffer gbuffer(w, h, layout);
    geometry.draw(gbuffer, camera);
    gl::Texture colour = gl::make_texture_2d(GL_RGBA32F, w, h);
    gl::Framebuffer fbo;
    glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0, colour.id(), 0);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
    glViewport(0, 0, w, h);
    lighting.draw(gbuffer, lights, scene.ambient, ch01::kBackground);
    ImageF out = ImageF::blank(w, h, 4);
    glGetTextureImage(colour.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(out.data.size() * sizeof(float)), out.data.data());
    flip_vertically(out);
    return out;
  }

  SurfaceImages surfaces(const FrameCamera& camera, const Layout& layout, int w = kW, int h = kH) {
    GBuffer gbuffer(w, h, layout);
    geometry.draw(gbuffer, camera);
    return probe.read(gbuffer);
  }

  Scene scene;
  SceneGpu gpu;
  ch01::ForwardRenderer forward;
  GeometryPass geometry;
  DeferredLighting lighting;
  SurfaceProbe probe;
  ch01::LightBuffer lights;
};

double angle_between(const glm::vec3& a, const glm::vec3& b) {
  return std::atan2(double(glm::length(glm::cross(a, b))), double(glm::dot(a, b)));
}

// The bound of `layout`'s normal encoding, as the GPU rounds it (the source's xyz: within one
// code, not half).
double normal_bound(const Layout& layout) {
  switch (layout.normal) {
    case NormalEncoding::Float: return 1e-6;
    case NormalEncoding::Xyz10: return std::asin(2 * std::sin(xyz_error_bound(10)));
    case NormalEncoding::Oct8: return octahedral_error_bound(8);
    case NormalEncoding::Oct10: return octahedral_error_bound(10);
    case NormalEncoding::Oct16: return octahedral_error_bound(16);
  }
  return 0;
}

// One pixel's stored surface against the exact one: within the format's bounds? (The first
// failure is reported.)
struct SurfaceValues { glm::vec3 n, albedo, specular; float exponent; };
bool stored_within_bounds(const Layout& layout, const SurfaceValues& exact, const SurfaceValues& got, int x, int y, bool report) {
  auto code = [&](float v) {
    return layout.colour_format == GL_SRGB8_ALPHA8 ? linear_to_srgb(std::clamp(v, 0.f, 1.f)) * 255.f : v * 255.f;
  };
  float colour_off = 0;
  for (int k = 0; k < 3 && layout.colour_format != GL_RGBA32F; ++k)
    colour_off = std::max({colour_off, std::abs(code(got.albedo[k]) - code(exact.albedo[k])),
                           std::abs(code(got.specular[k]) - code(exact.specular[k]))});
  const double exponent_off = std::abs(double(got.exponent) / exact.exponent - 1.0);
  const double normal_off = angle_between(got.n, exact.n);
  const bool ok = colour_off <= 1.f + 1e-3f && normal_off <= normal_bound(layout) + 1e-6 &&
                  (layout.colour_format == GL_RGBA32F || exponent_off <= exponent_relative_error_bound() * (1 + 1e-4));
  if (!ok && report)
    ADD_FAILURE() << layout.name << " (" << x << ", " << y << "): the GPU stored values beyond the format's bounds: colour "
                  << colour_off << " codes, exponent " << exponent_off << ", normal " << normal_off << " rad";
  return ok;
}

// [quantisation-bound]
// Each image's bytes come from the GPU's sRGB encoder, which need not round exactly: the
// usual hardware tolerance (Direct3D's, which GPUs follow) is 0.6 of a step, not 0.5, so two
// images may differ by 0.2 of a step more than their values do. (Plus 0.001 for the GPU and
// the CPU evaluating the same formula in a different order.)
constexpr float kEncodeSlack = 0.2f + 1e-3f;

// What the GPU stored may widen the allowance only as far as the format lets it: every stored
// value is first held to its format's bound against the exact one (colours within one code,
// OpenGL rounding anywhere within it; the exponent within its 1.8 %; the normal within its
// encoding's angle) -- a write-path bug fails there instead of widening its own allowance --
// and then may add at most kStoredExcess steps to what the C++ twin's codes allow. The two
// stored surfaces are then at most one code apart (the twin's within half a code of the exact
// value, the GPU's within one); measured on llvmpipe, the GPU's surface asks for 0.66 step more than
// the twin's at most, over every view here; one step leaves room for a GPU that rounds the
// other way everywhere, and no more.
constexpr float kStoredExcess = 1.f;

// What a layout's formats can change in the output, pixel by pixel, computed on the CPU with
// the C++ twins: the exact surface (the float layout, which equals forward's fragment inputs)
// is shaded once as it is and once as the layout stores it, colours, exponent and normal
// rounded by the same codes the shaders use, and the position anywhere within its
// reconstruction bound. The largest change, in continuous 8-bit sRGB steps, plus one for
// rounding both images (|round(a) - round(b)| < |a - b| + 1, and the
// encoder's slack above), is the most the deferred image may differ from the forward one.
std::vector<int> allowed_difference(const World& w, const SurfaceImages& exact, const Layout& layout, const FrameCamera& camera,
                                    const SurfaceImages& stored) {
  auto colour = [&](glm::vec3 c) {
    if (layout.colour_format == GL_RGBA32F) return c;
    for (int k = 0; k < 3; ++k) {
      float v = std::clamp(c[k], 0.f, 1.f);
      c[k] = layout.colour_format == GL_SRGB8_ALPHA8 ? srgb_to_linear(std::round(linear_to_srgb(v) * 255.f) / 255.f)
                                                     : std::round(v * 255.f) / 255.f;
    }
    return c;
  };
  auto normal = [&](glm::vec3 n) {
    switch (layout.normal) {
      case NormalEncoding::Float: return n;
      case NormalEncoding::Xyz10: return decode_xyz(encode_xyz(n, 10), 10);
      case NormalEncoding::Oct8: return decode_octahedral(encode_octahedral(n, 8), 8);
      case NormalEncoding::Oct10: return decode_octahedral(encode_octahedral(n, 10), 10);
      case NormalEncoding::Oct16: return decode_octahedral(encode_octahedral(n, 16), 16);
    }
    return n;
  };
  auto steps = [](glm::vec3 c) { return glm::clamp(glm::vec3(linear_to_srgb(c.r), linear_to_srgb(c.g), linear_to_srgb(c.b)), 0.f, 1.f) * 255.f; };
  const glm::vec3 eye = camera.position, forward_axis = -glm::vec3(glm::inverse(camera.view)[2]);
  std::vector<int> allowed(std::size_t(kW) * kH, 1);
  std::size_t stored_out_of_bounds = 0;
  for (int y = 0; y < exact.position.height; ++y)
    for (int x = 0; x < exact.position.width; ++x) {
      if (exact.sky(x, y)) continue;
      glm::vec3 p(exact.position.at(x, y, 0), exact.position.at(x, y, 1), exact.position.at(x, y, 2));
      glm::vec3 n(exact.normal.at(x, y, 0), exact.normal.at(x, y, 1), exact.normal.at(x, y, 2));
      glm::vec3 albedo(exact.albedo.at(x, y, 0), exact.albedo.at(x, y, 1), exact.albedo.at(x, y, 2));
      glm::vec3 spec(exact.specular.at(x, y, 0), exact.specular.at(x, y, 1), exact.specular.at(x, y, 2));
      glm::vec3 emissive(exact.emissive.at(x, y, 0), exact.emissive.at(x, y, 1), exact.emissive.at(x, y, 2));
      float exponent = exact.normal.at(x, y, 3);
      auto shade = [&](glm::vec3 pos, glm::vec3 nn, glm::vec3 a, glm::vec3 s, float e) {
        return ch01::shade({pos, nn, glm::normalize(eye - pos), a, s, e}, w.scene, emissive);
      };
      glm::vec3 truth = steps(shade(p, n, albedo, spec, exponent));
      double range = glm::length(p - eye), axial = glm::dot(p - eye, forward_axis);
      float reach = float(reconstruction_error_bound(layout.depth, camera.znear, camera.zfar, axial, range, glm::length(p)));
      if (layout.stored_position) reach = 0;
      // Two candidates for what the G-buffer holds: the C++ twin's codes, and what the GPU
      // stored (read back through decode_gbuffer). They differ where OpenGL leaves the
      // rounding to the implementation (float to 8-bit colour: llvmpipe may round x.4 up) or
      // where two normal codes are almost equally good and float rounding picks the other;
      // both are what the formats allow.
      struct Stored { glm::vec3 n, albedo, specular; float exponent; };
      Stored model{normal(n), colour(albedo), colour(spec),
                   layout.colour_format == GL_RGBA32F ? exponent : decode_exponent(encode_exponent(exponent))};
      Stored gpu{{stored.normal.at(x, y, 0), stored.normal.at(x, y, 1), stored.normal.at(x, y, 2)},
                 {stored.albedo.at(x, y, 0), stored.albedo.at(x, y, 1), stored.albedo.at(x, y, 2)},
                 {stored.specular.at(x, y, 0), stored.specular.at(x, y, 1), stored.specular.at(x, y, 2)},
                 stored.normal.at(x, y, 3)};
      const Stored candidates[2] = {model, gpu};
      // The reconstructed position lies anywhere within `reach` of the true one (not only
      // along the ray: the inverse view-projection's float arithmetic moves it sideways too);
      // to first order it changes the shading by |gradient| * reach, the gradient taken by
      // central differences over that ball.
      // The stored values within their format's bounds (see kStoredExcess).
      stored_out_of_bounds += !stored_within_bounds(layout, {n, albedo, spec, exponent}, {gpu.n, gpu.albedo, gpu.specular, gpu.exponent},
                                                    x, y, stored_out_of_bounds == 0);
      float worst = 0, model_worst = 0;
      for (const Stored& q : candidates) {
        auto shade_stored = [&](glm::vec3 pos) { return steps(shade(pos, q.n, q.albedo, q.specular, q.exponent)); };
        glm::vec3 at = shade_stored(p), gradient_sq(0);
        for (int k = 0; k < 3 && reach > 0; ++k) {
          glm::vec3 e(0);
          e[k] = reach;
          glm::vec3 g = (shade_stored(p + e) - shade_stored(p - e)) * 0.5f;
          gradient_sq += g * g;
        }
        glm::vec3 d = glm::abs(at - truth) + glm::sqrt(gradient_sq);
        const float here = std::max({d.r, d.g, d.b});
        if (&q == &candidates[0]) model_worst = here;
        worst = std::max(worst, std::min(here, model_worst + kStoredExcess));
      }
      allowed[std::size_t(y) * kW + x] = int(std::floor(worst + kEncodeSlack)) + 1;
    }
  EXPECT_EQ(stored_out_of_bounds, 0u) << layout.name << ": pixels whose stored values are beyond the format's bounds";
  return allowed;
}
// [/quantisation-bound]

struct Excess {
  std::size_t pixels = 0;  // pixels over their allowance
  int worst = 0;           // largest difference seen
  int worst_allowed = 0;   // largest allowance
  std::string first;
};

Excess over_allowance(const ImageRGBA8& a, const ImageRGBA8& b, const std::vector<int>& allowed) {
  Excess e;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      int d = 0;
      for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(int(a.at(x, y)[c]) - int(b.at(x, y)[c])));
      int limit = allowed[std::size_t(y) * a.width + x];
      e.worst = std::max(e.worst, d);
      e.worst_allowed = std::max(e.worst_allowed, limit);
      if (d > limit && e.pixels++ == 0) e.first = "(" + std::to_string(x) + ", " + std::to_string(y) + "): " + std::to_string(d) + " > " + std::to_string(limit);
    }
  return e;
}

// A camera `distance` metres from the scene's centre looking at it, with the design notes'
// near 0.1 m and far 1000 m.
Camera distant_camera(const Scene& scene, float distance) {
  glm::vec3 centre = (scene.bounds_min + scene.bounds_max) * 0.5f;
  float radius = glm::length(scene.bounds_max - scene.bounds_min) * 0.5f;
  glm::vec3 eye = centre + distance * glm::normalize(glm::vec3(0.35f, 0.45f, 1.f));
  Camera c;
  c.world = glm::inverse(glm::lookAt(eye, centre, glm::vec3(0, 1, 0)));
  c.yfov = 2.f * std::atan(0.8f * radius / distance);
  c.znear = 0.1f;
  c.zfar = 1000.f;
  return c;
}

// Eye 3 cm above the atrium floor, looking along it: the floor is seen at a grazing angle.
Camera grazing_camera() {
  Camera c;
  c.world = glm::inverse(glm::lookAt(glm::vec3(0.5f, 0.03f, 10.f), glm::vec3(0.5f, 0.f, -10.f), glm::vec3(0, 1, 0)));
  c.yfov = 0.7f;
  c.znear = 0.01f;
  c.zfar = 100.f;
  return c;
}

class GBufferGl : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    atrium_ = new World("assets/atrium/atrium.gltf");
    spheres_ = new World("assets/forward/forward.gltf");
  }
  static void TearDownTestSuite() {  // GL objects go before the context (gl_environment.h)
    delete spheres_;
    delete atrium_;
  }
  static World* atrium_;
  static World* spheres_;
};
World* GBufferGl::atrium_ = nullptr;
World* GBufferGl::spheres_ = nullptr;

}  // namespace

TEST_F(GBufferGl, EveryLayoutIsCompleteWithAStencilForTheNextChapter) {
  for (const auto& layout : layouts()) {
    GBuffer g(kW, kH, layout);  // throws when incomplete
    GLint stencil = 0, depth = 0;
    glGetTextureLevelParameteriv(g.depth_stencil(), 0, GL_TEXTURE_STENCIL_SIZE, &stencil);
    glGetTextureLevelParameteriv(g.depth_stencil(), 0, GL_TEXTURE_DEPTH_SIZE, &depth);
    EXPECT_GE(stencil, 8) << layout.name;
    EXPECT_GE(depth, 24) << layout.name;
    EXPECT_EQ(g.bytes_per_pixel(), bytes_per_pixel(layout));
  }
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

TEST_F(GBufferGl, FloatLayoutEqualsForwardUpToRounding) {
  // With nothing quantised (float targets, stored position) both images evaluate the same
  // formulas on the same inputs: they may differ only by how the last bit rounds, 1 step.
  for (const auto& view : {"overview", "aisle", "corner"}) {
    FrameCamera camera = atrium_->camera(view);
    CompareResult r = compare(atrium_->deferred_image(camera, float_layout()), atrium_->forward_image(camera),
                              {.threshold = 1, .max_failing_fraction = 0});
    EXPECT_TRUE(r.passed) << view << ": " << r.summary();
  }
}

TEST_F(GBufferGl, OurLayoutMatchesForwardWithinWhatItsFormatsLose) {
  struct Case { World* world; FrameCamera camera; std::string name; };
  std::vector<Case> cases = {
      {atrium_, atrium_->camera("overview"), "atrium overview"},
      {atrium_, atrium_->camera("aisle"), "atrium aisle"},
      {atrium_, frame_camera(grazing_camera(), float(kW) / kH), "atrium grazing floor"},
      {spheres_, spheres_->camera("close_128"), "glossy sphere"},
      {spheres_, spheres_->camera("grazing"), "forward grazing"},
  };
  for (const auto& c : cases) {
    std::vector<int> allowed = allowed_difference(*c.world, c.world->surfaces(c.camera, float_layout()), our_layout(), c.camera,
                                                  c.world->surfaces(c.camera, our_layout()));
    Excess e = over_allowance(c.world->deferred_image(c.camera, our_layout()), c.world->forward_image(c.camera), allowed);
    EXPECT_EQ(e.pixels, 0u) << c.name << ": first " << e.first << " (largest difference " << e.worst << ")";
    EXPECT_LE(e.worst_allowed, 4) << c.name << ": the formats should keep every pixel within a few steps";
    book_row("02_allowance", {{"view", c.name}},
             {{"largest_difference", double(e.worst)}, {"largest_allowance", double(e.worst_allowed)}, {"pixels_over", double(e.pixels)}});
  }
}

TEST_F(GBufferGl, StoredValuesStayWithinTheirFormatsBounds) {
  // What decode_gbuffer returns against the exact values (the float layout): colours within
  // one code (OpenGL lets the hardware round anywhere within a code), the exponent within
  // its 1.8 %, the normal within its encoding's angle. On the glossy spheres and on the
  // atrium's normal-mapped floor and walls (the normal the geometry pass builds from the map
  // is what is encoded).
  struct View { World* world; std::string name; };
  for (const View& v : {View{spheres_, "close_128"}, View{atrium_, "aisle"}, View{atrium_, "overview"}})
  for (const char* name : {"ours", "source", "srgb-colour", "oct8", "oct10", "xyz10"}) {
    FrameCamera camera = v.world->camera(v.name);
    SurfaceImages exact = v.world->surfaces(camera, float_layout());
    const Layout& layout = layout_named(name);
    SurfaceImages got = v.world->surfaces(camera, layout);
    double normal_bound = layout.normal == NormalEncoding::Xyz10 ? std::asin(2 * std::sin(xyz_error_bound(10)))
                          : layout.normal == NormalEncoding::Oct8 ? octahedral_error_bound(8)
                          : layout.normal == NormalEncoding::Oct10 ? octahedral_error_bound(10) : octahedral_error_bound(16);
    auto code = [&](float v) {  // the colour value in the format's own 8-bit steps
      return layout.colour_format == GL_SRGB8_ALPHA8 ? linear_to_srgb(std::clamp(v, 0.f, 1.f)) * 255.f : v * 255.f;
    };
    double colour = 0, exponent = 0, normal = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        if (exact.sky(x, y)) continue;
        for (int c = 0; c < 3; ++c) {
          colour = std::max(colour, double(std::abs(code(got.albedo.at(x, y, c)) - code(exact.albedo.at(x, y, c)))));
          colour = std::max(colour, double(std::abs(code(got.specular.at(x, y, c)) - code(exact.specular.at(x, y, c)))));
        }
        exponent = std::max(exponent, std::abs(double(got.normal.at(x, y, 3)) / exact.normal.at(x, y, 3) - 1.0));
        normal = std::max(normal, angle(glm::dvec3(got.normal.at(x, y, 0), got.normal.at(x, y, 1), got.normal.at(x, y, 2)),
                                        glm::dvec3(exact.normal.at(x, y, 0), exact.normal.at(x, y, 1), exact.normal.at(x, y, 2))));
      }
    EXPECT_LE(colour, 1.0 + 1e-3) << v.name << ", " << name;
    EXPECT_LE(exponent, exponent_relative_error_bound() * (1 + 1e-4)) << v.name << ", " << name;
    EXPECT_LE(normal, normal_bound + 1e-6) << v.name << ", " << name;
  }
}

TEST_F(GBufferGl, TheBoundSeparatesGoodFormatsFromBadOnes) {
  // The allowance is tight enough to catch a worse format: the 8-bit octahedral normal's
  // image falls outside the allowance computed for ours, on the glossy spheres.
  FrameCamera camera = spheres_->camera("close_128");
  SurfaceImages exact = spheres_->surfaces(camera, float_layout());
  std::vector<int> ours = allowed_difference(*spheres_, exact, our_layout(), camera, spheres_->surfaces(camera, our_layout()));
  Excess e = over_allowance(spheres_->deferred_image(camera, layout_named("oct8")), spheres_->forward_image(camera), ours);
  EXPECT_GT(e.pixels, 100u);
  book_row("02_allowance_oct8", {{"view", "glossy sphere"}}, {{"pixels_over_ours", double(e.pixels)}, {"largest_difference", double(e.worst)}});
  // ... and its own allowance explains it.
  std::vector<int> own = allowed_difference(*spheres_, exact, layout_named("oct8"), camera, spheres_->surfaces(camera, layout_named("oct8")));
  EXPECT_EQ(over_allowance(spheres_->deferred_image(camera, layout_named("oct8")), spheres_->forward_image(camera), own).pixels, 0u);
}

TEST_F(GBufferGl, GlslNormalEncodersStayWithinTheirBoundsOverTheWholeSphere) {
  // An odd-sized grid over the octahedral square: centre (+z), corners (-z), edges and
  // diagonals (the folds) are hit exactly. The GPU encodes into the real target format; the
  // codes are read back as integers and decoded with the C++ twin.
  const int n = 257;
  ShaderProgram program({{GL_VERTEX_SHADER, "02_gbuffer/shaders/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "02_gbuffer/shaders/encoding_check.frag"}});
  FullScreenPass quad;
  struct Case { int bits; GLenum format; double bound; };
  for (Case c : {Case{8, GL_RG8, octahedral_error_bound(8)}, Case{10, GL_RGB10_A2, octahedral_error_bound(10)},
                 Case{16, GL_RG16, octahedral_error_bound(16)}, Case{0, GL_RGB10_A2, std::asin(2 * std::sin(xyz_error_bound(10)))}}) {
    gl::Texture code = gl::make_texture_2d(c.format, n, n), direction = gl::make_texture_2d(GL_RGBA32F, n, n);
    gl::Framebuffer fbo;
    glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT0, code.id(), 0);
    glNamedFramebufferTexture(fbo.id(), GL_COLOR_ATTACHMENT1, direction.id(), 0);
    const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(fbo.id(), 2, buffers);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
    glViewport(0, 0, n, n);
    glDisable(GL_DEPTH_TEST);
    program.use();
    program.set("u_bits", c.bits);
    program.set("u_size", glm::vec2(n));
    quad.draw();
    glEnable(GL_DEPTH_TEST);
    std::vector<float> dirs(std::size_t(n) * n * 4);
    glGetTextureImage(direction.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(dirs.size() * 4), dirs.data());
    std::vector<std::uint32_t> codes(std::size_t(n) * n * 3);
    if (c.format == GL_RGB10_A2) {
      std::vector<std::uint32_t> packed(std::size_t(n) * n);
      glGetTextureImage(code.id(), 0, GL_RGBA, GL_UNSIGNED_INT_2_10_10_10_REV, GLsizei(packed.size() * 4), packed.data());
      for (std::size_t i = 0; i < packed.size(); ++i)
        for (int k = 0; k < 3; ++k) codes[i * 3 + k] = (packed[i] >> (10 * k)) & 1023u;
    } else {
      GLenum type = c.format == GL_RG8 ? GL_UNSIGNED_BYTE : GL_UNSIGNED_SHORT;
      std::vector<std::uint16_t> wide(std::size_t(n) * n * 2);
      std::vector<std::uint8_t> narrow(std::size_t(n) * n * 2);
      glPixelStorei(GL_PACK_ALIGNMENT, 1);
      if (type == GL_UNSIGNED_BYTE) glGetTextureImage(code.id(), 0, GL_RG, type, GLsizei(narrow.size()), narrow.data());
      else glGetTextureImage(code.id(), 0, GL_RG, type, GLsizei(wide.size() * 2), wide.data());
      for (std::size_t i = 0; i < std::size_t(n) * n; ++i)
        for (int k = 0; k < 2; ++k) codes[i * 3 + k] = type == GL_UNSIGNED_BYTE ? narrow[i * 2 + k] : wide[i * 2 + k];
    }
    double worst = 0;
    std::size_t same_as_cpu = 0;
    for (std::size_t i = 0; i < std::size_t(n) * n; ++i) {
      glm::vec3 d(dirs[i * 4], dirs[i * 4 + 1], dirs[i * 4 + 2]);
      glm::vec3 back;
      if (c.bits == 0) {
        // The source's mapping leaves the rounding to the hardware, and OpenGL lets it round
        // anywhere within a code (llvmpipe writes 836 for 835.4): one code, not half.
        back = decode_xyz({codes[i * 3], codes[i * 3 + 1], codes[i * 3 + 2]}, 10);
        XyzCode cpu = encode_xyz(d, 10);
        same_as_cpu += std::abs(int(cpu.x) - int(codes[i * 3])) <= 1 && std::abs(int(cpu.y) - int(codes[i * 3 + 1])) <= 1 &&
                       std::abs(int(cpu.z) - int(codes[i * 3 + 2])) <= 1;
      } else {
        back = decode_octahedral({codes[i * 3], codes[i * 3 + 1]}, c.bits);
        OctCode cpu = encode_octahedral(d, c.bits);
        same_as_cpu += cpu.x == codes[i * 3] && cpu.y == codes[i * 3 + 1];
      }
      worst = std::max(worst, angle(glm::dvec3(d), glm::dvec3(back)));
    }
    std::string name = c.bits ? "octahedral " + std::to_string(c.bits) : "xyz 10";
    EXPECT_LE(worst, c.bound) << name;
    // GLSL and C++ pick the same code nearly everywhere: where two codes are almost equally
    // good, float rounding may pick the other (0.15 % of the 8-bit codes on an NVIDIA H200,
    // fewer on llvmpipe). Our octahedral codes are written as exact fractions
    // code / (2^bits - 1), which survive any rounding the hardware does.
    EXPECT_GE(double(same_as_cpu), 0.99 * n * n) << name;
  }
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

TEST_F(GBufferGl, DecodedNormalsMatchTheFloatReferenceWithinTheEncodingBound) {
  // Through the whole pipeline (geometry pass, target, decode_gbuffer), on the glossy sphere.
  FrameCamera camera = spheres_->camera("close_128");
  SurfaceImages truth = spheres_->surfaces(camera, float_layout());
  for (const char* name : {"ours", "oct8", "oct10", "xyz10"}) {
    const Layout& layout = layout_named(name);
    SurfaceImages got = spheres_->surfaces(camera, layout);
    // The source's xyz leaves rounding to the hardware: within one code, not half.
    double bound = layout.normal == NormalEncoding::Xyz10 ? std::asin(2 * std::sin(xyz_error_bound(10)))
                   : layout.normal == NormalEncoding::Oct8 ? octahedral_error_bound(8)
                   : layout.normal == NormalEncoding::Oct10 ? octahedral_error_bound(10) : octahedral_error_bound(16);
    double worst = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        if (truth.sky(x, y)) continue;
        glm::dvec3 a(truth.normal.at(x, y, 0), truth.normal.at(x, y, 1), truth.normal.at(x, y, 2));
        glm::dvec3 b(got.normal.at(x, y, 0), got.normal.at(x, y, 1), got.normal.at(x, y, 2));
        worst = std::max(worst, angle(a, b));
      }
    EXPECT_LE(worst, bound + 1e-6) << name;  // + float rounding of the two normalisations
    EXPECT_GT(worst, 0.0) << name;
  }
}

TEST_F(GBufferGl, SkyIsMarkedExactlyWhereNothingWasDrawnAndIsNeverLit) {
  FrameCamera camera = atrium_->camera("aisle");
  std::vector<int> ids = ch01::render_instance_ids(atrium_->gpu, camera, kW, kH);
  std::size_t sky_pixels = 0;
  for (int id : ids) sky_pixels += id == 0;
  ASSERT_GT(sky_pixels, std::size_t(kW) * kH / 10) << "the atrium has no roof: the aisle view sees sky";
  for (const auto& layout : layouts()) {
    SurfaceImages s = atrium_->surfaces(camera, layout);
    ImageF lit = atrium_->deferred_linear(camera, layout);
    std::size_t wrong = 0, not_background = 0, non_finite = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        bool sky = ids[std::size_t(y) * kW + x] == 0;
        wrong += s.sky(x, y) != sky;
        for (int c = 0; c < 4; ++c) non_finite += !std::isfinite(lit.at(x, y, c));
        for (const ImageF* img : {&s.position, &s.normal, &s.albedo, &s.specular, &s.emissive})
          for (int c = 0; c < 4; ++c) non_finite += !std::isfinite(img->at(x, y, c));
        if (sky)
          for (int c = 0; c < 3; ++c) not_background += lit.at(x, y, c) != ch01::kBackground[c];
      }
    EXPECT_EQ(wrong, 0u) << layout.name << ": is_sky must be exactly the pixels no instance covers";
    EXPECT_EQ(not_background, 0u) << layout.name << ": sky pixels get the background, unlit";
    EXPECT_EQ(non_finite, 0u) << layout.name;
  }
}

TEST_F(GBufferGl, FarSurfacesNeedReversedZ) {
  // The atrium seen from 300 m (near 0.1 m, far 1000 m): standard depth loses centimetres,
  // reversed-Z D32F keeps float's relative precision. Each stays within its stated bound.
  FrameCamera camera = frame_camera(distant_camera(atrium_->scene, 300.f), float(kW) / kH);
  SurfaceImages truth_d24 = atrium_->surfaces(camera, float_layout());
  // Each format is compared with a float reference that made the same depth-test decisions
  // (D24, or reversed-Z D32F): what is left is the reconstruction alone.
  SurfaceImages truth_reversed = atrium_->surfaces(camera, float_reference_for(layout_named("reversed-z")));
  struct Errors { double p99 = 0; std::size_t pixels = 0, over_bound = 0, other_surface = 0; };
  auto errors = [&](const Layout& layout) {
    const SurfaceImages& truth = is_reversed_z(layout) ? truth_reversed : truth_d24;
    SurfaceImages got = atrium_->surfaces(camera, layout);
    std::vector<double> e;
    Errors r;
    glm::dvec3 eye(camera.position), axis = -glm::dvec3(glm::inverse(glm::dmat4(camera.view))[2]);
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        if (truth.sky(x, y)) continue;
        glm::dvec3 q(truth.position.at(x, y, 0), truth.position.at(x, y, 1), truth.position.at(x, y, 2));
        glm::dvec3 p(got.position.at(x, y, 0), got.position.at(x, y, 1), got.position.at(x, y, 2));
        glm::dvec3 n(truth.normal.at(x, y, 0), truth.normal.at(x, y, 1), truth.normal.at(x, y, 2));
        glm::dvec3 m(got.normal.at(x, y, 0), got.normal.at(x, y, 1), got.normal.at(x, y, 2));
        if (angle(n, m) > 0.035) {  // 2 degrees: another surface won the depth test here
          ++r.other_surface;
          continue;
        }
        double err = glm::length(p - q);
        e.push_back(err);
        double b = reconstruction_error_bound(layout.depth, camera.znear, camera.zfar, glm::dot(q - eye, axis), glm::length(q - eye), glm::length(q));
        r.over_bound += err > b;
      }
    std::sort(e.begin(), e.end());
    r.pixels = e.size();
    r.p99 = e[std::size_t(0.99 * e.size())];
    return r;
  };
  Errors d24 = errors(our_layout()), reversed = errors(layout_named("reversed-z"));
  ASSERT_GT(d24.pixels, 5000u);
  EXPECT_EQ(d24.over_bound, 0u);
  EXPECT_EQ(reversed.over_bound, 0u);
  EXPECT_EQ(d24.other_surface, 0u);
  EXPECT_EQ(reversed.other_surface, 0u);
  double p99_d24 = d24.p99, p99_reversed = reversed.p99;
  EXPECT_GT(p99_d24, 0.01) << "D24 at 300 m with near 0.1 m: centimetres";
  EXPECT_LT(p99_reversed * 100, p99_d24);
  // The image still matches forward within what the formats lose.
  std::vector<int> allowed = allowed_difference(*atrium_, truth_d24, our_layout(), camera, atrium_->surfaces(camera, our_layout()));
  Excess e = over_allowance(atrium_->deferred_image(camera, our_layout()), atrium_->forward_image(camera), allowed);
  EXPECT_EQ(e.pixels, 0u) << e.first;
}

TEST_F(GBufferGl, MeshWithoutTangentsOrUvsGivesFiniteUnitNormals) {
  // Two floor quads with a normal-mapped material but no usable tangent frame: one with a
  // zero tangent, one with its tangent along the normal, all UVs 0 (as a mesh without UVs is
  // loaded). The geometry pass must keep the interpolated normal, not write NaN.
  Scene s;
  s.path = "generated/no_tangents.gltf";
  auto quad = [&](glm::vec3 offset, glm::vec4 tangent) {
    std::uint32_t base = std::uint32_t(s.vertices.size());
    for (glm::vec2 c : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)})
      s.vertices.push_back({offset + glm::vec3(c.x, 0, c.y), glm::vec3(0, 1, 0), glm::vec2(0), tangent});
    for (std::uint32_t i : {0u, 2u, 1u, 0u, 3u, 2u}) s.indices.push_back(base + i);
  };
  quad({-1.2f, 0, 0}, glm::vec4(0, 0, 0, 0));
  quad({1.2f, 0, 0}, glm::vec4(0, 1, 0, 1));
  Texture bumpy;
  bumpy.name = "bumpy";
  bumpy.image = ImageRGBA8::blank(2, 2);
  for (int i = 0; i < 4; ++i) {
    std::uint8_t* p = bumpy.image.pixels.data() + i * 4;
    p[0] = 200; p[1] = 60; p[2] = 180; p[3] = 255;  // a strongly tilted normal
  }
  s.textures.push_back(bumpy);
  s.materials.push_back(Material{.name = "mapped", .base_color = glm::vec4(0.7f), .normal_texture = 0});
  s.materials.push_back(Material{.name = "default"});
  s.meshes.push_back(Mesh{"quads", {Primitive{0, 12, 0}}});
  s.instances.push_back(Instance{.name = "quads", .mesh = 0});
  s.lights.push_back(Light{.name = "sun", .type = LightType::Directional, .intensity = 1.f, .direction = glm::normalize(glm::vec3(0.3f, -1, 0.2f))});
  s.lights.push_back(Light{.name = "lamp", .type = LightType::Point, .intensity = 1.f, .position = glm::vec3(0, 0.5f, 0)});
  Camera c;
  c.name = "above";
  c.world = glm::inverse(glm::lookAt(glm::vec3(0, 3, 2), glm::vec3(0), glm::vec3(0, 1, 0)));
  s.cameras.push_back(c);
  s.bounds_min = glm::vec3(-2.2f, 0, -1);
  s.bounds_max = glm::vec3(2.2f, 0, 1);
  World world(std::move(s));
  FrameCamera camera = world.camera("above");
  for (const auto& layout : layouts()) {
    SurfaceImages got = world.surfaces(camera, layout);
    ImageF lit = world.deferred_linear(camera, layout);
    std::size_t drawn = 0, bad = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        for (int k = 0; k < 4; ++k) bad += !std::isfinite(lit.at(x, y, k));
        if (got.sky(x, y)) continue;
        ++drawn;
        glm::dvec3 n(got.normal.at(x, y, 0), got.normal.at(x, y, 1), got.normal.at(x, y, 2));
        bad += !(std::abs(glm::length(n) - 1.0) < 1e-3) || angle(n, {0, 1, 0}) > octahedral_error_bound(8);
      }
    EXPECT_GT(drawn, 2000u) << layout.name;
    EXPECT_EQ(bad, 0u) << layout.name;
  }
}

TEST_F(GBufferGl, LoadedMeshWithoutNormalsTangentsOrUvsRendersFinite) {
  World world("tests/data/nonindexed_nonormals.gltf");
  FrameCamera camera = frame_camera(world.scene.cameras.front(), float(kW) / kH);
  ImageF lit = world.deferred_linear(camera, our_layout());
  std::size_t bad = 0;
  for (float v : lit.data) bad += !std::isfinite(v);
  EXPECT_EQ(bad, 0u);
  ImageRGBA8 deferred = world.deferred_image(camera, our_layout());
  CompareResult r = compare(deferred, world.forward_image(camera), {.threshold = 2, .max_failing_fraction = 0});
  EXPECT_TRUE(r.passed) << r.summary();
}

TEST_F(GBufferGl, PassesLeaveOpenGLsDefaultDepthConvention) {
  GBuffer reversed(kW, kH, layout_named("reversed-z"));
  atrium_->geometry.draw(reversed, atrium_->camera("overview"));
  GLint clip_depth = 0, func = 0;
  glGetIntegerv(GL_CLIP_DEPTH_MODE, &clip_depth);
  glGetIntegerv(GL_DEPTH_FUNC, &func);
  EXPECT_EQ(clip_depth, GL_NEGATIVE_ONE_TO_ONE);
  EXPECT_EQ(func, GL_LESS);
  // The stencil is cleared to 0 and left alone, for chapter 03.
  std::vector<std::uint8_t> stencil(std::size_t(kW) * kH, 7);
  glBindFramebuffer(GL_FRAMEBUFFER, reversed.framebuffer());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, kW, kH, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, stencil.data());
  EXPECT_EQ(std::count(stencil.begin(), stencil.end(), 0), kW * kH);
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

TEST_F(GBufferGl, FragmentCountsAreExact) {
  // The geometry pass draws what forward draws (same vertex shader, same depth test): the
  // same fragments. The lighting pass shades every pixel exactly once.
  FrameCamera camera = atrium_->camera("overview");
  GBuffer gbuffer(kW, kH);
  OutputTarget target(kW, kH);
  PassMetrics m;
  target.bind();
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  { auto p = m.pass("forward"); atrium_->forward.draw(camera, ch01::ForwardMode::PerPixel, atrium_->lights); }
  { auto p = m.pass("geometry"); atrium_->geometry.draw(gbuffer, camera); }
  target.bind();
  { auto p = m.pass("lighting"); atrium_->lighting.draw(gbuffer, atrium_->lights, atrium_->scene.ambient, ch01::kBackground); }
  m.end_frame();
  m.wait_all();
  EXPECT_EQ(m.find("geometry")->samples, m.find("forward")->samples);
  EXPECT_GT(m.find("geometry")->samples, std::uint64_t(kW) * kH / 2);
  EXPECT_EQ(m.find("lighting")->samples, std::uint64_t(kW) * kH);
}

// The source layout stores an emissive strength s in the albedo target's alpha and decodes the
// emission as albedo x s: a tint of the albedo (the limit the palette removes). On the street,
// whose windows and lamps glow, every decoded emissive pixel is the decoded albedo times the
// alpha the target holds, to float rounding (the decode's product: half an ulp; 2^-23 relative
// allowed). The street's glowing materials have dark albedos, so a strength not tinted by the
// albedo (s alone) is far from it.
TEST_F(GBufferGl, SourceLayoutsEmissiveIsItsAlbedoScaled) {
  World street("assets/street/street.gltf");
  FrameCamera camera = street.camera("street_level");
  GBuffer gbuffer(kW, kH, layout_named("source"));
  street.geometry.draw(gbuffer, camera);
  SurfaceImages s = street.probe.read(gbuffer);
  ImageF stored = ImageF::blank(kW, kH, 4);
  glGetTextureImage(gbuffer.albedo(), 0, GL_RGBA, GL_FLOAT, GLsizei(stored.data.size() * sizeof(float)), stored.data.data());
  flip_vertically(stored);  // as the probe's images: rows top to bottom
  std::size_t glowing = 0, dark = 0, off = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const float strength = stored.at(x, y, 3);
      if (s.sky(x, y) || strength <= 0.f) continue;
      ++glowing;
      dark += std::max({s.albedo.at(x, y, 0), s.albedo.at(x, y, 1), s.albedo.at(x, y, 2)}) < 0.9f;
      for (int c = 0; c < 3; ++c) {
        const float want = s.albedo.at(x, y, c) * strength, got = s.emissive.at(x, y, c);
        if (std::abs(got - want) > 0x1p-23f * std::abs(want) && off++ < 3)
          ADD_FAILURE() << "(" << x << ", " << y << ") channel " << c << ": emissive " << got << ", albedo x strength " << want;
      }
    }
  std::printf("source layout on the street: %zu emissive pixels, %zu of them with an albedo below 0.9\n", glowing, dark);
  EXPECT_GT(dark, 100u);
  EXPECT_EQ(off, 0u);
}

TEST_F(GBufferGl, StreetEmissiveViewMatchesItsReference) {
  // The atrium has no emissive material; the street's windows and lamps do. Their colours are
  // not tints of their albedo (dark glass glowing orange), which the source's albedo-scaled
  // strength cannot store: our palette code keeps them exactly.
  World street("assets/street/street.gltf");
  FrameCamera camera = street.camera("street_level");
  GBuffer gbuffer(kW, kH);
  street.geometry.draw(gbuffer, camera);
  OutputTarget target(kW, kH);
  target.bind();
  BufferViewPass view;
  view.draw(gbuffer, BufferView::Emissive, ch01::kBackground);
  ImageRGBA8 image = target.read();
  auto reference = source_root() / "tests" / "reference" / "02_gbuffer" / "street_level_emissive.png";
  if (std::getenv("LIGHTPASS_UPDATE_REFERENCES")) save_png(reference, image);
  ASSERT_TRUE(std::filesystem::exists(reference)) << "missing " << reference << " (make it on purpose: LIGHTPASS_UPDATE_REFERENCES=1)";
  CompareResult r = compare(image, load_png(reference));
  if (!r.passed) save_png(std::filesystem::temp_directory_path() / "street_level_emissive.png", image);
  EXPECT_TRUE(r.passed) << r.summary();
  std::size_t glowing = 0;
  for (int i = 0; i < kW * kH; ++i) glowing += image.pixels[i * 4] > 100;
  EXPECT_GT(glowing, 200u) << "windows and lamps should glow in the emissive view";
  // Exact: the emissive decoded from the palette equals the material's colour.
  SurfaceImages s = street.probe.read(gbuffer), truth = street.surfaces(camera, float_layout());
  double worst = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      for (int c = 0; c < 3; ++c) worst = std::max(worst, double(std::abs(s.emissive.at(x, y, c) - truth.emissive.at(x, y, c))));
  EXPECT_EQ(worst, 0.0);
}
