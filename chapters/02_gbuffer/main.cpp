// Chapter 02: the G-buffer and deferred shading. The frame is two passes: the geometry pass
// draws every object once into the G-buffer (albedo, specular, normal, depth: no lighting),
// then one full-screen pass lights every pixel from it. The modes show the lit result, the
// thesis's layout, chapter 01's forward image and the difference, and each buffer.
#include <iostream>
#include <memory>
#include <set>
#include <sstream>

#include "chapters/01_forward/forward.h"
#include "chapters/01_forward/ground_truth.h"
#include "chapters/01_forward/light_buffer.h"
#include "chapters/02_gbuffer/deferred.h"
#include "chapters/02_gbuffer/gbuffer.h"
#include "common/app.h"
#include "common/target.h"

#include <imgui.h>

namespace {

using namespace lp;
using namespace lp::ch02;

std::vector<std::string> modes() {
  std::vector<std::string> m = {"deferred", "layout-source", "ambient-directional", "forward", "difference"};
  m.insert(m.end(), kBufferViews.begin(), kBufferViews.end());
  m.push_back("mosaic");  // the lit image among its buffers
  return m;
}

std::vector<std::string> layout_names() {
  std::vector<std::string> names;
  for (const auto& l : layouts()) names.push_back(l.name);
  return names;
}

// [references]
// The atrium's views sample its floor's textures far away: another renderer gets
// kMinifiedTextureAllowance there (common/app.h).
std::vector<Shot> references() {
  const CompareOptions textured_floor = kMinifiedTextureAllowance;
  std::vector<Shot> shots = {{"overview", "deferred", {}, {}, textured_floor},
                             {"aisle", "deferred", {}, {}, textured_floor},
                             {"corner", "deferred", {}, {}, textured_floor},
                             {"aisle", "layout-source", {}, {}, textured_floor},
                             {"overview", "ambient-directional", {}, {}, textured_floor},
                             {"corner", "deferred", {{"layout", 8}}, {}, textured_floor}};  // reversed-Z: the same image
  for (const auto& view : kBufferViews) {
    bool textured = view == "albedo" || view == "normal";
    Shot shot{"aisle", view};
    if (textured) shot.other_renderer = textured_floor;
    shots.push_back(shot);
  }
  shots.push_back({"corner", "normal", {{"layout", 4}}, {}, textured_floor});  // octahedral 8+8
  shots.push_back({"overview", "mosaic", {}, {}, textured_floor});  // the opening, the README's picture
  return shots;
}
// [/references]

const lp::Chapter kChapter{
    .cli = {.program = "02_gbuffer",
            .summary = "The G-buffer and deferred shading: one geometry pass, one lighting pass, every buffer shown.",
            .default_scene = "assets/atrium/atrium.gltf",
            .modes = modes(),
            .knobs = {{"lights", "lights to use (0: the scene's own; more adds point lights)", 0, 0, 100000, true},
                      choice_knob("layout", "G-buffer layout (the table in the book)", layout_names())},
            // The lit image among the buffers it is computed from: alone it looks like forward shading.
            .opening = {"--mode", "mosaic"}},
    .references = references(),
    // The street's emissive buffer: its windows and lamps (a palette code each), the image
    // the GL test StreetEmissiveViewMatchesItsReference also holds in-process.
    .scene_references = {{"assets/street/street.gltf", {{"street_level", "emissive"}}}},
    // [exercises]
    .exercises = {{.title = "the octahedral encoding of a normal (the fold)",
                   .file = "octahedral_fold.glsl",
                   .define = "EXERCISE_OCTAHEDRAL_FOLD",
                   .shots = {{"aisle", "normal", {}, {}, kMinifiedTextureAllowance}, {"overview", "deferred", {}, {}, kMinifiedTextureAllowance}},
                   .look_at = "the normal buffer (--mode normal): surfaces facing away from +z, and the lighting that follows them"},
                  {.title = "decoding the octahedral normal (the unfold)",
                   .file = "octahedral_unfold.glsl",
                   .define = "EXERCISE_OCTAHEDRAL_UNFOLD",
                   .shots = {{"aisle", "normal", {}, {}, kMinifiedTextureAllowance}, {"overview", "deferred", {}, {}, kMinifiedTextureAllowance}},
                   .look_at = "the normal buffer (--mode normal): the colours of walls and floors that face down or away (the folded half)"},
                  {.title = "the world position from the depth buffer",
                   .file = "reconstruct_position.glsl",
                   .define = "EXERCISE_RECONSTRUCT_POSITION",
                   .shots = {{"overview", "deferred", {}, {}, kMinifiedTextureAllowance},
                             {"corner", "deferred", {{"layout", 8}}, {}, kMinifiedTextureAllowance}},  // reversed-Z
                   .look_at = "where the lights fall off and the highlights sit; the second view uses reversed-Z depth (--layout reversed-z)"}},
    // [/exercises]
};

const Layout& layout_for(const Frame& f) {
  return f.mode == "layout-source" ? source_layout() : layouts()[std::size_t(f.knob_int("layout"))];
}

void bind_output(const Frame& f) {
  glBindFramebuffer(GL_FRAMEBUFFER, f.target);
  glViewport(0, 0, f.width, f.height);
  glEnable(GL_FRAMEBUFFER_SRGB);
}

// The heat map of |deferred - forward| (largest channel difference, 8 full scale) shown in
// the output: both images are rendered, read back and compared like the tests do.
class DifferenceView {
 public:
  void draw(const Frame& f, const ImageRGBA8& deferred, const ImageRGBA8& forward) {
    ImageRGBA8 heat = diff_heatmap(deferred, forward, 1, 8);
    flip_vertically(heat);
    texture_ = gl::make_texture_2d(GL_SRGB8_ALPHA8, f.width, f.height);  // the bytes are display values
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(texture_.id(), 0, 0, 0, f.width, f.height, GL_RGBA, GL_UNSIGNED_BYTE, heat.pixels.data());
    fbo_ = gl::Framebuffer();
    glNamedFramebufferTexture(fbo_.id(), GL_COLOR_ATTACHMENT0, texture_.id(), 0);
    glBlitNamedFramebuffer(fbo_.id(), f.target, 0, 0, f.width, f.height, 0, 0, f.width, f.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  }

 private:
  gl::Texture texture_{GL_TEXTURE_2D};
  gl::Framebuffer fbo_;
};

// --mode mosaic's tiles, left to right, top to bottom: the lit image, the buffers, chapter 01's.
const std::vector<std::string> kMosaic = {"deferred", "albedo", "specular", "normal", "depth", "exponent",
                                          "position", "ambient-directional", "forward"};

}  // namespace

int main(int argc, char** argv) {
  return lp::run_chapter(argc, argv, kChapter, [](lp::App& app) {
    GeometryPass geometry(app.scene_gpu());
    DeferredLighting lighting;
    BufferViewPass views;
    ch01::ForwardRenderer forward(app.scene_gpu());
    DifferenceView difference;
    std::unique_ptr<OutputTarget> tile;  // --mode mosaic: each picture at full size, then shrunk into its tile
    ch01::LightBuffer lights;
    std::unique_ptr<GBuffer> gbuffer;
    std::set<std::string> reported;
    int light_count = -1;
    const glm::vec3 background = ch01::kBackground, ambient = app.scene().ambient;

    while (app.next_frame()) {
      const lp::Frame& f = app.frame();
      if (f.reload_shaders) {
        geometry.reload_shaders();
        lighting.reload_shaders();
        views.reload_shaders();
        forward.reload_shaders();
      }
      if (f.knob_int("lights") != light_count) {
        light_count = f.knob_int("lights");
        lights.upload(ch01::lights_for_count(app.scene(), light_count));
      }
      const Layout& layout = layout_for(f);
      if (!gbuffer || gbuffer->width() != f.width || gbuffer->height() != f.height || gbuffer->layout().name != layout.name) {
        gbuffer = std::make_unique<GBuffer>(f.width, f.height, layout);
        app.metrics().set_allocation("G-buffer (" + layout.name + ")", gbuffer->bytes_per_pixel() * f.width * f.height);
        if (reported.insert(layout.name).second) {
          std::cout << "G-buffer layout '" << layout.name << "': " << gbuffer->bytes_per_pixel() << " bytes per pixel =";
          for (const auto& t : targets(layout)) std::cout << ' ' << t.name << ' ' << t.format << " (" << t.bytes << ")";
          std::cout << '\n';
        }
      }

      // [frame]
      if (f.mode == "forward") {  // chapter 01's forward shading, for comparison
        glClearColor(background.r, background.g, background.b, 1.f);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        auto pass = app.metrics().pass("forward: all lights in one pass");
        forward.draw(f.camera, ch01::ForwardMode::PerPixel, lights);
      } else {
        {
          auto pass = app.metrics().pass("geometry: fill the G-buffer");
          geometry.draw(*gbuffer, f.camera);
        }
        bind_output(f);
        if (is_buffer_view(f.mode)) {
          auto pass = app.metrics().pass("show the " + f.mode + " buffer");
          views.draw(*gbuffer, buffer_view(f.mode), background);
        } else {
          auto pass = app.metrics().pass("lighting: full-screen pass");
          LightSelection which = f.mode == "ambient-directional" ? LightSelection::AmbientAndDirectional : LightSelection::All;
          lighting.draw(*gbuffer, lights, ambient, background, which);
        }
      }
      // [/frame]
      if (f.mode == "mosaic") {  // the G-buffer just drawn, each picture of it in a tile, captioned
        if (!tile || tile->width() != f.width || tile->height() != f.height)
          tile = std::make_unique<OutputTarget>(f.width, f.height);
        bind_output(f);
        glClear(GL_COLOR_BUFFER_BIT);
        for (std::size_t i = 0; i < kMosaic.size(); ++i) {
          const std::string& picture = kMosaic[i];
          tile->bind();
          glClearColor(background.r, background.g, background.b, 1.f);
          glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
          if (picture == "forward") forward.draw(f.camera, ch01::ForwardMode::PerPixel, lights);
          else if (picture == "deferred") lighting.draw(*gbuffer, lights, ambient, background, LightSelection::All);
          else if (picture == "ambient-directional")
            lighting.draw(*gbuffer, lights, ambient, background, LightSelection::AmbientAndDirectional);
          else views.draw(*gbuffer, buffer_view(picture), background);
          const int col = int(i % 3), row = int(i / 3);  // row 0 at the top; OpenGL's rows start at the bottom
          glBlitNamedFramebuffer(tile->framebuffer(), f.target, 0, 0, f.width, f.height, col * f.width / 3,
                                 (2 - row) * f.height / 3, (col + 1) * f.width / 3, (3 - row) * f.height / 3,
                                 GL_COLOR_BUFFER_BIT, GL_LINEAR);
        }
        ImageRGBA8 img = read_framebuffer(f.target, f.width, f.height);
        for (std::size_t i = 0; i < kMosaic.size(); ++i) {
          const std::string& m = kMosaic[i];
          const std::string caption = m == "deferred"              ? "lit (deferred)"
                                      : m == "forward"             ? "forward (ch. 1)"
                                      : m == "ambient-directional" ? "no local lights"
                                                                   : m;
          draw_label(img, int(i % 3) * f.width / 3 + 1, int(i / 3) * f.height / 3 + 1, caption);
        }
        put_picture(img, f.target);
        bind_output(f);
      }
      if (f.mode == "difference") {  // the same frame forward, and the heat map of the two
        OutputTarget reference(f.width, f.height);
        reference.bind();
        glClearColor(background.r, background.g, background.b, 1.f);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        forward.draw(f.camera, ch01::ForwardMode::PerPixel, lights);
        ImageRGBA8 forward_image = reference.read();
        ImageRGBA8 deferred_image = ImageRGBA8::blank(f.width, f.height);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        bind_output(f);
        glReadPixels(0, 0, f.width, f.height, GL_RGBA, GL_UNSIGNED_BYTE, deferred_image.pixels.data());
        flip_vertically(deferred_image);
        difference.draw(f, deferred_image, forward_image);
        ImageRGBA8 keyed = read_framebuffer(f.target, f.width, f.height);  // the heat map's legend, in the picture
        draw_heat_key(keyed, {.full_scale = 8, .what = "|deferred - forward|, largest channel, 8-bit steps", .threshold = 1});
        put_picture(keyed, f.target);
        bind_output(f);
      }

      app.panel([&] {
        ImGui::Text("%d lights, G-buffer '%s': %zu bytes/pixel", lights.count(), layout.name.c_str(), gbuffer->bytes_per_pixel());
        ImGui::TextWrapped("%s", layout.description.c_str());
      });
    }
  });
}
