// Chapter 06: shadows. Chapter 03's deferred frame with a stage that draws the sun's depth
// map from an orthographic frustum fitted to what the view needs, and the frame's light
// shaders look each pixel up in it by the method the mode names: one comparison (hard),
// k x k comparisons (pcf), the hardware's comparison sampler (pcf-hardware), Chebyshev's bound
// on filtered moments (vsm), filtered exp(c z) in log space (esm), four moments and the Hamburger
// reconstruction (msm), or PCF over the penumbra a
// blocker search finds for the sun as a disk (pcss); or with no map, by the sun's shadow volumes
// counted in the stencil (volumes). The sun casts, and the spot lights the scene marks (a
// perspective map each in a tile of one atlas, hard or PCF; --spots all: every spot light), and
// the point lights it marks (a cube map each; --points all:
// every point light); the other local lights keep chapter 03's path (visibility 1). The ray-traced truth that the tests
// and the sweep measure against is shadow_truth.h.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <memory>
#include <iostream>
#include <string>
#include <vector>

#include <imgui.h>

#include "chapters/03_light_volumes/light_radius.h"
#include "chapters/06_shadows/shadow_stage.h"
#include "chapters/06_shadows/shadow_truth.h"
#include "common/target.h"
#include "common/app.h"
#include "common/error.h"
#include "common/image.h"

namespace {

using namespace lp;
using namespace lp::ch06;

enum Show { kResult, kVisibility, kMap, kTruth, kSoftTruth, kError, kCascades };  // --show's order

// The truth's channel as grey, blue where the sun does not reach (as show_visibility.frag).
ImageRGBA8 truth_picture(const ImageF& truth, int channel) {
  ImageRGBA8 out = ImageRGBA8::blank(truth.width, truth.height);
  for (int y = 0; y < truth.height; ++y)
    for (int x = 0; x < truth.width; ++x) {
      std::uint8_t* p = out.at(x, y);
      const bool outside = truth.at(x, y, 2) < 0.5f;
      const auto g = std::uint8_t(std::clamp(truth.at(x, y, channel), 0.f, 1.f) * 255.f + 0.5f);
      p[0] = outside ? 89 : g, p[1] = outside ? 108 : g, p[2] = outside ? 170 : g, p[3] = 255;  // linear 0.1, 0.15, 0.4
    }
  return out;
}

// The scene's lights with every directional light's intensity times `sun` (chapter 05's --sun).
std::vector<Light> scaled_lights(const std::vector<Light>& lights, float sun) {
  std::vector<Light> out = lights;
  for (Light& l : out)
    if (l.type == LightType::Directional) l.intensity *= sun;
  return out;
}

const CliSpec kCli{
    .program = "06_shadows",
    .summary = "Shadows from the sun in the deferred frame: a depth map from a fitted orthographic frustum, looked up "
               "with one comparison, PCF, the hardware comparison sampler, VSM, ESM, four moments (MSM) or PCSS; or shadow volumes.",
    .default_scene = "assets/atrium/atrium.gltf",
    .modes = {"pcf", "hard", "pcf-hardware", "vsm", "esm", "volumes", "pcss", "msm", "csm-fourier"},  // the chapter's recommendation first
    .knobs = {{"map", "shadow map width and height in texels (8192: 1.3 GiB with vsm or esm)", 1024, 16, 8192, true},
              {"kernel", "pcf: the k x k grid; vsm, esm: the box filter's width (odd)", 3, 1, 31, true},
              {"taps", "pcf: 0 for the k x k grid, or this many taps of a Poisson disk k texels across, rotated per "
                       "pixel; pcss: the taps of its blocker search and of its filter (0: 32)", 0, 0, 64, true},
              {"sun-size", "the sun's angular radius in radians: pcss's light and the soft truth's disk (the real sun: "
                           "0.0047)", kSunAngularRadius, 0, 0.2, false},
              {"bias", "constant depth bias, in texels of the map", 0.5, 0, 100, false},
              {"slope", "slope-scaled bias, in texels per unit tan(theta)", 1, 0, 100, false},
              {"normal", "normal offset, in texels", 1, 0, 100, false},
              {"pmin", "vsm: light-bleeding reduction (p_max below it is shadow)", 0.2, 0, 0.99, false},
              {"c", "esm: the exponent of exp(c z) (z: window depth in [0, 1]); any c works in log space", 80, 1, 10000,
               false},
              {"fit", "fit the map's box to the view (off: to the whole scene)", 1, 0, 1, true},
              {"moments", "vsm, esm: bits per value of the filtered map, 32 (RG32F) or 16 (RG16F, half the bytes); msm: "
                          "RGBA32F or RGBA16 through the optimised map", 32,
               16, 32, true},
              {"cascades", "cascaded maps for the sun, each --map texels a side (1: one map fitted to the view; "
                           "methods hard, pcf, pcf-hardware, pcss)", 1, 1, kMaxCascades, true},
              {"lambda", "cascades: the split, 0 uniform to 1 logarithmic", 0.75, 0, 1, false},
              {"snap", "cascades: each box on whole texels (0: shimmers as the camera moves)", 1, 0, 1, true},
              {"band", "cascades: the blend band, a fraction of each cascade's depth range", 0.1, 0, 0.5, false},
              {"shadow-distance", "cascades: metres of view depth they cover (0: the far plane or the scene's "
                                  "farthest corner)", 0, 0, 100000, false},
              {"terms", "csm-fourier: the terms of the step's Fourier series (two channels of the map each)", 4, 1,
               kMaxCsmTerms, true},
              choice_knob("points", "which point lights cast, each from a cube map: those the scene marks "
                                    "(casts_shadows; the atrium marks none), or every point light (up to 8)",
                          {"marked", "all"}),
              {"cube", "point lights: a cube map face's width and height in texels", 512, 16, 4096, true},
              choice_knob("spots", "which spot lights cast, each from a tile of one atlas --map texels a side: "
                                   "those the scene marks (casts_shadows), or every spot light (up to 16)",
                          {"marked", "all"}),
              {"sun", "multiplies directional lights, times what the scene asks for (the atrium: 4, its 0.4 lux "
                      "sun beside eight point lights shows the shadows only faintly at 1; other scenes: 1)", 1, 0, 1000,
               false},
              choice_knob("show", "the image; the sun's visibility alone (blue: sky or facing away); the depth map "
                                  "itself (near black, far white); the ray-traced hard or soft truth (the sun as a disk of "
                                  "--sun-size; ray traced on the CPU: "
                                  "seconds per view); |visibility - truth| as a heat map (hard truth for hard, "
                                  "soft for the others; red = 1); the visibility tinted by the cascade each pixel "
                                  "reads (red, green, blue, yellow)",
                          {"result", "visibility", "map", "truth", "soft-truth", "error", "cascades"})}};

// [references]
// The atrium in sunlight: every method from above, the hard and filtered methods and PCSS in
// the aisle among the columns, and the visibility term alone.
// The lit views see the atrium's tiled floor minified into the distance:
// kMinifiedTextureAllowance (common/app.h) on another renderer.
const CompareOptions kTexturedFloor = kMinifiedTextureAllowance;

std::vector<Shot> atrium_shots() {
  std::vector<Shot> shots;
  for (const std::string& m : kMethodNames) shots.push_back({"overview", m, {}, {}, kTexturedFloor});
  shots.push_back({"aisle", "hard", {}, {}, kTexturedFloor});
  shots.push_back({"aisle", "vsm", {}, {}, kTexturedFloor});
  shots.push_back({"aisle", "pcss", {}, {}, kTexturedFloor});  // contact hardening: the column bases' sharp shadows
  shots.push_back({"corner", "pcf", {{"show", kVisibility}}});
  shots.push_back({"overview", "hard", {{"show", kMap}}});
  // The eight point lights casting from cube maps (the atrium marks none: --points all).
  shots.push_back({"overview", "pcf", {{"points", 1}}, {}, kTexturedFloor});
  return shots;
}
// [/references]

// The exercises (the book's "Exercises"): three functions of shadow_visibility.glsl, each
// checked where its mistake shows, and one number.
std::vector<Exercise> exercises() {
  return {{.title = "the map lookup's normal offset and slope-scaled bias",
           .file = "shadow_lookup.glsl",
           .define = "EXERCISE_SHADOW_LOOKUP",
           .shots = {{"overview", "hard", {}, {}, kTexturedFloor}, {"corner", "hard", {{"show", kVisibility}}}},
           .look_at = "the lit floor and walls (--show visibility): acne, stripes of shadow on surfaces the sun lights, "
                      "worst where it grazes them"},
          {.title = "variance shadow maps: Chebyshev's bound and the bleeding reduction",
           .file = "vsm_bound.glsl",
           .define = "EXERCISE_VSM_BOUND",
           .shots = {{"overview", "vsm", {}, {}, kTexturedFloor}, {"aisle", "vsm", {{"show", kVisibility}}}},
           .look_at = "the shadows (--mode vsm --show visibility): whether there are any, their soft edges, and light "
                      "bleeding where the columns' shadows overlap"},
          {.title = "PCF's receiver plane: the depth gradient across the kernel",
           .file = "receiver_plane.glsl",
           .define = "EXERCISE_RECEIVER_PLANE",
           .shots = {{"overview", "pcf", {{"kernel", 7}, {"show", kVisibility}}}, {"corner", "pcf", {{"kernel", 7}, {"show", kVisibility}}}},
           .look_at = "the surfaces the sun grazes (--kernel 7 --show visibility): a dark fringe of self-shadow, or "
                      "shadows that lose their contact"},
          {.title = "the practical split: where cascade 1 ends (a number)",
           .file = "cascade_split.txt",
           .look_at = "shadow_math.h's [cascades]: z_1 blends the logarithmic and the uniform split, i = 1 of 4",
           .number = NumberAnswer{.expected = [] { return double(cascade_splits(4, 0.5f, 80.f, 0.75f)[1]); },
                                  .tolerance = 0.01,
                                  .unit = "m"}}};
}

const Chapter kChapter{.cli = kCli, .references = atrium_shots(), .exercises = exercises()};

// --show cascades' key: the tints of show_visibility.frag's SHOW_CASCADES (lit; through the sRGB
// target), grey beyond the last cascade, the blue of the sky and of faces turned from the sun.
void draw_cascades_key(ImageRGBA8& picture, int cascades) {
  const auto srgb = srgb_colour;
  const std::array<std::uint8_t, 3> tints[4] = {srgb(1.f, 0.3f, 0.3f), srgb(0.3f, 1.f, 0.3f), srgb(0.35f, 0.45f, 1.f),
                                                srgb(1.f, 0.9f, 0.2f)};
  std::vector<LegendEntry> key;
  for (int i = 0; i < std::min(cascades, 4); ++i) key.push_back({tints[i], "cascade " + std::to_string(i)});
  if (cascades > 1) key.push_back({srgb(0.5f, 0.5f, 0.5f), "beyond the last cascade"});
  key.push_back({srgb(0.1f, 0.15f, 0.4f), "sky, or facing away from the sun"});
  key.push_back({std::nullopt, "darker: in shadow (30 % in full)"});
  draw_legend(picture, key);
}

// --show visibility's key: show_visibility.frag writes the sun's visibility as grey (through the
// sRGB target) and the blue of the sky and of faces turned from the sun.
void draw_visibility_key(ImageRGBA8& picture) {
  const auto srgb = srgb_colour;
  draw_legend(picture, {{srgb(1.f, 1.f, 1.f), "lit by the sun (visibility 1)"},
                        {srgb(0.5f, 0.5f, 0.5f), "half lit (0.5: a penumbra)"},
                        {srgb(0.f, 0.f, 0.f), "black: in the sun's shadow (0)"},
                        {srgb(0.1f, 0.15f, 0.4f), "sky, or facing away from the sun"}});
}

}  // namespace

int main(int argc, char** argv) {
  return run_chapter(argc, argv, kChapter, [](App& app) {
    const Light& sun = find_sun(app.scene());
    // The scene's own sun scale (the atrium's 4), never a default for every scene: a model's
    // sun or the default rig at 4 times would clip to white.
    const float scene_scale = scene_sun_scale(app.scene());
    if (scene_scale != 1.f)
      std::cerr << "06_shadows: directional lights x" << scene_scale << ", as " << app.scene().path.filename().string()
                << " asks (extras.lightpass.shadows_sun_scale); --sun multiplies that\n";
    ch03::DeferredFrame frame(app.scene_gpu());
    float sun_scale = -1.f;  // the lights are built on the first frame, and again when --sun changes
    ShadowStage shadows(app.scene_gpu(), sun);
    // [marked-lights]
    // The lights the scene marks (shadow_stage.h [casts-shadows]): the sun casts unless marked
    // not to, and then the frame is chapter 03's; a marked light this chapter has no map for is
    // named, and keeps chapter 03's path.
    const bool sun_casts = casts_shadows(app.scene(), std::size_t(&sun - app.scene().lights.data()));
    if (sun_casts) frame.add_stage(shadows);
    else std::cerr << "06_shadows: the sun '" << sun.name << "' is marked casts_shadows: false: no shadows (chapter 03's frame)\n";
    for (const std::string& note : unshadowed_casters(app.scene())) std::cerr << "06_shadows: " << note << '\n';
    // [/marked-lights]
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);

    bool first_frame = true;
    std::unique_ptr<RayScene> rays;  // the truth's, made when a truth is first shown
    ImageF truth;
    glm::mat4 truth_camera{0};
    float truth_sun_size = -1.f;
    while (app.next_frame()) {
      const Frame& f = app.frame();
      const auto start = std::chrono::steady_clock::now();
      if (f.reload_shaders) {
        frame.reload_shaders();
        shadows.reload_shaders();
      }
      if (f.knob_int("map") > max_size)
        throw UsageError("--map " + std::to_string(f.knob_int("map")) + " is larger than this OpenGL's "
                         "GL_MAX_TEXTURE_SIZE, " + std::to_string(max_size));
      // An even kernel on the command line is bad usage; the window's slider passing one on
      // the way is taken as the next odd one.
      if (first_frame && f.knob_int("kernel") % 2 == 0)
        throw UsageError("--kernel must be odd (a grid centred on the lookup), not " + std::to_string(f.knob_int("kernel")));
      const int kernel = f.knob_int("kernel") | 1;
      if (first_frame && f.knob_int("moments") != 16 && f.knob_int("moments") != 32)
        throw UsageError("--moments must be 16 or 32, not " + std::to_string(f.knob_int("moments")));
      const int moment_bits = f.knob_int("moments") < 24 ? 16 : 32;  // the window's slider: the nearer one
      if (float(f.knob("sun")) != sun_scale) {
        const bool first = sun_scale < 0.f;
        sun_scale = float(f.knob("sun"));
        ch03::use_lights(frame, app.scene(), scaled_lights(app.scene().lights, sun_scale * scene_scale), first);
      }
      first_frame = false;
      // [settings]
      const ShadowSettings settings{.method = method_from_name(f.mode),
                                    .map_size = f.knob_int("map"),
                                    .kernel = kernel,
                                    .poisson_taps = f.knob_int("taps"),
                                    .sun_angular_radius = float(f.knob("sun-size")),
                                    .constant_bias = float(f.knob("bias")),
                                    .slope_bias = float(f.knob("slope")),
                                    .normal_offset = float(f.knob("normal")),
                                    .p_min = float(f.knob("pmin")),
                                    .c = float(f.knob("c")),
                                    .fit_to_view = f.knob_int("fit") != 0,
                                    .moment_bits = moment_bits,
                                    .cascades = f.knob_int("cascades"),
                                    .cascade_lambda = float(f.knob("lambda")),
                                    .cascade_distance = float(f.knob("shadow-distance")),
                                    .cascade_band = float(f.knob("band")),
                                    .cascade_snap = f.knob_int("snap") != 0,
                                    .all_point_lights = f.knob_int("points") == 1,
                                    .cube_size = f.knob_int("cube"),
                                    .csm_terms = f.knob_int("terms"),
                                    .all_spot_lights = f.knob_int("spots") == 1};
      const int show = f.knob_int("show");
      const bool cascadable = settings.method == ShadowMethod::Hard || settings.method == ShadowMethod::Pcf ||
                              settings.method == ShadowMethod::PcfHardware || settings.method == ShadowMethod::Pcss;
      if (settings.cascades > 1 && !cascadable)
        throw UsageError("--cascades " + std::to_string(settings.cascades) + " needs the mode hard, pcf, pcf-hardware or "
                         "pcss (" + f.mode + (settings.method == ShadowMethod::Volumes ? " has no map)" : "'s filtered map is one layer)"));
      if (!sun_casts && show != kResult)
        throw Error(knob_text(kCli, "show", f.knob("show")) + " shows the sun's shadows, and the scene marks the sun '" +
                    sun.name + "' casts_shadows: false");
      shadows.set(settings, show == kVisibility ? ShadowPicture::Visibility
                            : show == kMap      ? ShadowPicture::Map
                            : show == kCascades ? ShadowPicture::Cascades
                                                : ShadowPicture::None);
      frame.render(f.camera, {f.target, f.width, f.height}, &app.metrics());
      // [/settings]
      if (show == kCascades || show == kVisibility) {
        ImageRGBA8 picture = read_framebuffer(f.target, f.width, f.height);
        if (show == kCascades) draw_cascades_key(picture, settings.cascades);
        else draw_visibility_key(picture);
        put_picture(picture, f.target);
      }
      // [truth-view]
      if (show >= kTruth && show <= kError) {
        // The truth for this camera and size: traced once per view (cached on disk headless).
        if (!rays) rays = std::make_unique<RayScene>(app.scene());
        const glm::mat4 key = f.camera.projection * f.camera.view;
        const TruthSettings disk{.angular_radius = settings.sun_angular_radius};
        if (truth.width != f.width || truth.height != f.height || key != truth_camera ||
            disk.angular_radius != truth_sun_size) {
          truth = app.options().headless
                      ? cached_shadow_truth(app.scene(), *rays, f.camera, f.width, f.height, sun.direction, disk)
                      : shadow_truth(app.scene(), *rays, f.camera, f.width, f.height, sun.direction, disk);
          truth_camera = key;
          truth_sun_size = disk.angular_radius;
        }
        if (show == kError) {
          ColourTarget visibility(f.width, f.height, GL_RGBA32F);
          shadows.set(settings, ShadowPicture::Visibility);
          frame.render(f.camera, {visibility.framebuffer(), f.width, f.height});
          const ImageF v = visibility.read();
          const int channel = settings.method == ShadowMethod::Hard ? 0 : 1;
          std::vector<float> error(std::size_t(f.width) * std::size_t(f.height), 0.f);
          for (int y = 0; y < f.height; ++y)
            for (int x = 0; x < f.width; ++x)
              if (truth.at(x, y, 2) > 0.5f)
                error[std::size_t(y) * f.width + x] = std::abs(v.at(x, y, 0) - truth.at(x, y, channel));
          const VisibilityError e = visibility_error(v, truth, channel);
          if (std::ostream& out = app.report())
            out << "against the " << (channel == 0 ? "hard" : "soft") << " truth: mean |error| " << e.mean_abs
                << ", p99 " << e.p99 << ", " << 100 * e.wrong << "% of " << e.pixels << " pixels wrong by > 0.5\n";
          ImageRGBA8 heat = error_heatmap(error, f.width, f.height, 1.f);
          draw_heat_key(heat, {.full_scale = 1, .what = channel == 0 ? "|visibility - hard truth|" : "|visibility - soft truth|"});
          put_picture(heat, f.target);
        } else {
          put_picture(truth_picture(truth, show == kTruth ? 0 : 1), f.target);
        }
      }
      // [/truth-view]
      app.metrics().set_allocation("shadow map (chapter 06)", shadows.allocated_bytes());
      app.metrics().set_allocation("G-buffer (chapter 02) + light buffer (chapter 03)", frame.allocated_bytes());
      if (std::ostream& out = app.report()) {
        glFinish();
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        if (settings.method == ShadowMethod::Volumes)
          out << "sun shadow volumes: " << shadows.volume_stats().cap_triangles << " cap triangles, "
              << shadows.volume_stats().side_quads << " sides to infinity, no map (" << shadows.allocated_bytes() / 1024
              << " KiB); frame took " << ms << " ms (wall clock, " << app.context().renderer() << ")\n";
        else
        out << "sun shadows, " << f.mode << ": map " << settings.map_size << "x" << settings.map_size << " ("
            << shadows.allocated_bytes() / 1024 << " KiB), " << shadows.frustum().texel_world(settings.map_size) * 100.f
            << " cm per texel; frame took " << ms << " ms (wall clock, " << app.context().renderer() << ")\n";
        if (!shadows.point_lights().empty())
          out << "  point lights: " << shadows.point_lights().size() << " cube maps of 6 x " << settings.cube_size << "x"
              << settings.cube_size << ", " << std::count(shadows.points_mapped().begin(), shadows.points_mapped().end(), true)
              << " drawn this frame\n";
        if (!shadows.spot_lights().empty())
          out << "  spot lights: " << shadows.spot_lights().size() << " tiles of " << shadows.spot_tile(0).size << "x"
              << shadows.spot_tile(0).size << " in a " << settings.map_size << "x" << settings.map_size << " atlas, "
              << std::count(shadows.spots_mapped().begin(), shadows.spots_mapped().end(), true) << " drawn this frame\n";
        const auto& cascades = shadows.cascades();
        for (std::size_t i = 0; i < cascades.size(); ++i)
          out << "  cascade " << i << ": view depth " << shadows.cascade_splits()[i] << " to "
              << shadows.cascade_splits()[i + 1] << " m, " << cascades[i].texel_world(settings.map_size) * 100.f
              << " cm per texel\n";
      }
      app.panel([&] {
        ImGui::Text("sun map %dx%d, %.1f cm per texel", settings.map_size, settings.map_size,
                    shadows.frustum().texel_world(settings.map_size) * 100.f);
        ImGui::Text("%zu KiB for the sun's maps", shadows.allocated_bytes() / 1024);
        for (std::size_t i = 0; i < shadows.cascades().size(); ++i)
          ImGui::Text("cascade %zu: to %.1f m, %.1f cm per texel", i, shadows.cascade_splits()[i + 1],
                      shadows.cascades()[i].texel_world(settings.map_size) * 100.f);
      });
    }
  });
}
