// Chapter 11: time. Chapter 10's whole frame, each frame's projection moved by a sub-pixel
// jitter (Halton 2, 3), motion vectors drawn after the G-buffer, and temporal anti-aliasing
// after the composite: the history moved by the motion, read through a Catmull-Rom filter,
// clipped to this frame's neighbourhood in YCoCg, dropped where the surface was hidden last
// frame, blended in a tonemapped space (taa.h). `--path walk` plays a camera path of the scene
// (camera_path.h) frame by frame, in the window and headless (`--frames N` plays N frames,
// `--at F` starts at the path's frame F after drawing the frames before it, `--strip K` writes
// every K-th frame into a strip PNG). `--show motion` draws the motion vectors, `--show
// rejected` where the history was dropped, `--show truth` the supersampled truth TAA tends to.
// `--accumulate gi` (the default) accumulates chapter 08's AO and indirect light over frames too
// (temporal_gi.h), `--accumulate all` chapter 06's PCSS for the sun as well (temporal_shadows.h;
// `--pcss 1` alone: PCSS with every tap each frame). The program opens on `--view shop_window --show split`: the middle magnified
// (--zoom), without AA beside TAA, settled (headless, the frames before the still are drawn first).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>

#include <imgui.h>

#include "chapters/11_temporal/camera_path.h"
#include "chapters/11_temporal/measure.h"
#include "chapters/11_temporal/motion_picture.h"
#include "chapters/11_temporal/temporal_frame.h"
#include "common/app.h"
#include "common/error.h"
#include "common/target.h"

namespace {

using namespace lp;
using namespace lp::ch11;

enum Show { kImage, kMotion, kRejected, kSplit, kTruth };  // --show's order
constexpr int kMaxStripFrames = 16;
constexpr float kMotionFullScalePixels = 8.f;  // --show motion: this many pixels a frame is full colour
// --show split/truth headless on a still view: the TAA frames drawn before the one written (two
// periods of the jitter; at --alpha 0.1 the first frame keeps 0.9^16 = 19 % of its weight).
constexpr int kSettleFrames = 16;

const CliSpec kCli{
    .program = "11_temporal",
    .summary = "Time: chapter 10's whole frame with sub-pixel jitter, motion vectors and temporal anti-aliasing; "
               "--path plays a camera path of the scene frame by frame.",
    .default_scene = "assets/street_shop/street_shop.gltf",
    .modes = {"whole"},
    .knobs = {choice_knob("path", "a camera path of the scene, one path frame per frame (off: the view, or the "
                                  "window's fly camera)",
                          path_names()),
              {"at", "with --path: the first frame shown is the path's frame AT (the frames before it drawn first)", 0, 0, 1000, true},
              {"strip", "headless, with --path: every STRIP-th path frame drawn goes into <out>_strip.png (0: none)", 0, 0, 1000, true},
              {"taa", "temporal anti-aliasing (off: chapter 10's frame, no jitter)", 1, 0, 1, true},
              choice_knob("filter", "how the history is read between its texels", {"bilinear", "catmull-rom"}, 1),
              choice_knob("clip", "the history held to this frame's 3x3 neighbourhood: not, clamped per RGB channel, "
                                  "or clipped towards the box's centre in YCoCg",
                          {"off", "rgb-clamp", "ycocg-clip"}, 2),
              {"reject", "drop the history where the surface was hidden last frame (depth test)", 1, 0, 1, true},
              {"alpha", "this frame's weight in the blend", 0.1, 0.01, 1},
              choice_knob("show", "the image; the motion vectors (hue: direction, full colour: 8 pixels a frame); "
                                  "where the history was dropped (red); the image without AA beside TAA's; the "
                                  "supersampled truth (16 frames a frame: slow)",
                          {"image", "motion", "rejected", "split", "truth"}),
              {"zoom", "--show split and truth: the image's middle magnified ZOOM times, pixels as squares (the edges' steps)", 4, 1, 8, true},
              {"shadows", "the sun's shadow map (chapter 06)", 1, 0, 1, true},
              {"ao", "ambient occlusion (chapters 07, 08)", 1, 0, 1, true},
              {"indirect", "one bounce of indirect light (chapter 08)", 1, 0, 1, true},
              choice_knob("accumulate", "accumulated over frames: nothing; chapter 08's AO and indirect light (4 "
                                        "samples a frame, a part of a 32-point pattern, turned; off: its 32 every "
                                        "frame); those and the sun's soft shadow (chapter 06's PCSS, 4 taps of its "
                                        "32-tap disk a frame for the search and the filter, turned; sets --pcss 1)",
                          {"off", "gi", "all"}, 1),
              {"pcss", "the sun's shadow soft: chapter 06's PCSS, its 32 taps every frame (off: chapter 10's PCF 3x3)",
               0, 0, 1, true},
              {"neon", "chapter 04's tubes", 1, 0, 1, true},
              {"glow", "multiplies emissive surfaces (chapter 05)", 8, 0, 10000},
              choice_knob("bloom", "chapter 05's bloom: off, after tonemapping, or before", {"off", "after", "before"}, 2)},
    // The chapter's subject is an edge without its steps: it opens on the shop's shelf of
    // bottles, magnified, without AA beside TAA.
    .opening = {"--view", "shop_window", "--show", "split"}};

int path_index(const char* name) {
  const std::vector<std::string> names = path_names();
  return int(std::find(names.begin(), names.end(), name) - names.begin());
}

// The references: the first frame (one jittered frame), and the walk after a dozen frames with
// TAA, without, and where its history was dropped; the opening (the README's picture).
std::vector<Shot> shots(const char* view) {
  const double walk = path_index("walk");
  return {{view, "whole", {}},
          {view, "whole", {{"path", walk}, {"at", 12}}},
          {view, "whole", {{"path", walk}, {"at", 12}, {"taa", 0}}},
          {view, "whole", {{"path", walk}, {"at", 12}, {"show", kRejected}}},
          {"shop_window", "whole", {{"show", kSplit}}}};
}

// The exercises (the book's "Exercises"): the motion vector and two steps of the resolve, each
// checked on the walk after a dozen frames, where a wrong history shows.
std::vector<Exercise> exercises() {
  const double walk = path_index("walk");
  const Shot image{"shops", "whole", {{"path", walk}, {"at", 12}}};
  return {{.title = "a surface point's motion vector",
           .file = "motion_of.glsl",
           .define = "EXERCISE_MOTION_OF",
           .shots = {image, {"shops", "whole", {{"path", walk}, {"at", 12}, {"show", kMotion}}}},
           .look_at = "the motion (--path walk --show motion: hue is the direction) and the walk's edges, smeared "
                      "or doubled where the history is read from the wrong place"},
          {.title = "clipping the history to this frame's neighbourhood",
           .file = "clip_to_box.glsl",
           .define = "EXERCISE_CLIP_TO_BOX",
           .shots = {image, {"shops", "whole", {{"path", walk}, {"at", 4}}}},
           .look_at = "the walk's first frames (--path walk --at 4): ghosts of the street trailing behind edges"},
          {.title = "was this surface hidden last frame?",
           .file = "disoccluded.glsl",
           .define = "EXERCISE_DISOCCLUDED",
           .shots = {image, {"shops", "whole", {{"path", walk}, {"at", 12}, {"show", kRejected}}}},
           .look_at = "where the history is dropped (--path walk --show rejected: red), beside the edges that "
                      "the walk uncovers"}};
}

const Chapter kChapter{.cli = kCli, .references = shots("shops"), .exercises = exercises()};

TemporalSettings settings_of(const Frame& f) {
  TemporalSettings s;
  s.whole = {.shadows = f.knob_int("shadows") != 0, .ao = f.knob_int("ao") != 0, .indirect = f.knob_int("indirect") != 0,
             .neon = f.knob_int("neon") != 0, .glow = float(f.knob("glow"))};
  s.whole.hdr.bloom = static_cast<ch05::BloomMode>(f.knob_int("bloom"));
  s.gi.enabled = f.knob_int("accumulate") >= 1;
  s.shadows.enabled = f.knob_int("accumulate") == 2;
  s.pcss = f.knob_int("pcss") != 0 || s.shadows.enabled;
  s.taa = {.enabled = f.knob_int("taa") != 0,
           .alpha = float(f.knob("alpha")),
           .filter = static_cast<HistoryFilter>(f.knob_int("filter")),
           .clip = static_cast<HistoryClip>(f.knob_int("clip")),
           .reject_disocclusion = f.knob_int("reject") != 0};
  return s;
}

// --show motion: each pixel's motion in pixels a frame, its direction as hue, with its key.
ImageRGBA8 read_motion_picture(GLuint motion, int w, int h) {
  std::vector<float> m(std::size_t(w) * h * 4);
  glGetTextureImage(motion, 0, GL_RGBA, GL_FLOAT, GLsizei(m.size() * sizeof(float)), m.data());
  ImageRGBA8 out = ch11::motion_picture(m, w, h, kMotionFullScalePixels);
  draw_direction_key(out, motion_key(kMotionFullScalePixels));
  return out;
}

// --show rejected's key: what red is, and what the rest of the picture is.
void draw_rejected_key(ImageRGBA8& image) { draw_legend(image, ch11::rejected_key()); }

// --show rejected: the image darkened, the pixels whose history was dropped red, and its key.
void mark_rejected(GLuint rejected, GLuint target, int w, int h) {
  std::vector<std::uint8_t> r(std::size_t(w) * h);
  glGetTextureImage(rejected, 0, GL_RED, GL_UNSIGNED_BYTE, GLsizei(r.size()), r.data());
  ImageRGBA8 image = read_framebuffer(target, w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = image.at(x, y);
      const bool dropped = r[std::size_t(h - 1 - y) * w + x] > 127;
      for (int c = 0; c < 3; ++c) p[c] = dropped ? (c == 0 ? 255 : 0) : std::uint8_t(p[c] / 3);
    }
  draw_rejected_key(image);
  put_picture(image, target);
}

// --zoom: the picture's middle magnified `zoom` times, each pixel a square.
ImageRGBA8 magnified(const ImageRGBA8& image, int zoom) {
  if (zoom <= 1) return image;
  ImageRGBA8 out = image;
  const int w = image.width, h = image.height;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int sx = std::clamp(w / 2 + int(std::floor(double(x - w / 2) / zoom)), 0, w - 1);
      const int sy = std::clamp(h / 2 + int(std::floor(double(y - h / 2) / zoom)), 0, h - 1);
      std::copy_n(image.at(sx, sy), 4, out.at(x, y));
    }
  return out;
}

// --show split: the middle halves of the image without AA and with TAA side by side, captioned.
ImageRGBA8 split_picture(const ImageRGBA8& plain, const ImageRGBA8& taa, int zoom) {
  ImageRGBA8 out = plain;
  const int w = plain.width, half = w / 2, from = w / 4;
  for (int y = 0; y < plain.height; ++y) {
    std::copy_n(plain.at(from, y), std::size_t(half) * 4, out.at(0, y));
    std::copy_n(taa.at(from, y), std::size_t(w - half) * 4, out.at(half, y));
  }
  const std::string times = zoom > 1 ? ", x" + std::to_string(zoom) : "";
  draw_label(out, 2, 2, "no AA" + times);
  draw_label(out, half + 2, 2, "TAA" + times);
  return out;
}

std::string strip_path(const Options& o, const std::string& program) {
  std::filesystem::path out = o.out.empty() ? std::filesystem::path(default_output(program + ".png")) : std::filesystem::path(o.out);
  return (out.parent_path() / (out.stem().string() + "_strip.png")).string();
}

}  // namespace

int main(int argc, char** argv) {
  return run_chapter(argc, argv, kChapter, [](App& app) {
    // 1. Chapter 10's whole frame with this chapter's two stages: motion and TAA.
    TemporalFrame frame(app.scene_gpu());
    std::unique_ptr<TemporalFrame> plain;   // --show split: the frame without AA; --show truth: the still frames
    std::unique_ptr<OutputTarget> plain_target;
    int path_frame = 0;            // the next frame of the path to draw
    std::vector<ImageRGBA8> strip; // --strip: the frames kept, left to right
    bool strip_full = false;

    while (app.next_frame()) {
      const Frame& f = app.frame();
      if (f.reload_shaders) frame.reload_shaders();
      const TemporalSettings s = settings_of(f);
      const ch03::FrameOutput output{f.target, f.width, f.height};
      const std::string& path_name = f.choice("path");
      const int strip_every = f.knob_int("strip");
      const int show = f.knob_int("show");
      const bool taa = s.taa.enabled;
      if ((show == kSplit || show == kTruth) && !plain) plain = std::make_unique<TemporalFrame>(app.scene_gpu());
      FrameCamera shown = f.camera;  // the camera of the frame shown
      bool shown_cut = f.new_shot;
      // 2. The camera: the path's frame (and whether it cuts), or the view / fly camera.
      if (path_name == "off") {
        // Headless, the split is of TAA settled: the frames before the still drawn first.
        const bool settle = show == kSplit && taa && f.new_shot && !app.context().is_window();
        for (int k = 0; settle && k < kSettleFrames; ++k) frame.render(f.camera, output, s, f.dt, k == 0);
        frame.render(f.camera, output, s, f.dt, f.new_shot && !settle, &app.metrics());
      } else {
        const CameraPath& path = path_named(app.options().scene, path_name);
        auto camera_at = [&](int i) {
          return frame_camera(path.camera(app.scene(), i), float(f.width) / float(f.height));
        };
        auto keep = [&](int i) {  // --strip: this path frame, read back
          if (strip_every <= 0 || app.context().is_window() || app.options().check || i % strip_every != 0) return;
          if (int(strip.size()) >= kMaxStripFrames) { strip_full = true; return; }
          strip.push_back(read_framebuffer(f.target, f.width, f.height));
        };
        if (f.new_shot) {
          // The frames before --at, drawn as they would have been, so the history is theirs.
          const int at = std::min(f.knob_int("at"), path.frames() - 1);
          for (int i = 0; i < at; ++i) {
            frame.render(camera_at(i), output, s, 1.f / path.fps, path.cut_at(i));
            keep(i);
          }
          path_frame = at;
        }
        const int i = path_frame % path.frames();  // the window plays it again and again
        shown = camera_at(i);
        shown_cut = path.cut_at(i) || (i == 0 && !f.new_shot);
        frame.render(shown, output, s, 1.f / path.fps, shown_cut, &app.metrics());
        keep(i);
        if (std::ostream& out = app.report())
          out << "path " << path.name << ": frame " << i << " of " << path.frames() << " (" << path.fps << " fps)"
              << (path.cut_at(i) ? ", a cut" : "") << '\n';
        ++path_frame;
      }
      // 3. The pictures: the motion vectors, where the history was dropped, the image without AA
      // beside TAA's, or the truth; these two magnified by --zoom.
      if (show == kMotion && taa) put_picture(read_motion_picture(frame.motion().current(), f.width, f.height), f.target);
      if (show == kRejected && taa) mark_rejected(frame.taa().rejected(), f.target, f.width, f.height);
      if ((show == kMotion || show == kRejected || show == kSplit) && !taa)
        app.report() << "note: --show " << f.choice("show") << " needs --taa 1\n";
      const int zoom = f.knob_int("zoom");
      if (show == kSplit && taa) {
        if (!plain_target || plain_target->width() != f.width || plain_target->height() != f.height)
          plain_target = std::make_unique<OutputTarget>(f.width, f.height);
        TemporalSettings none = s;
        none.taa.enabled = false;
        plain->render(shown, {plain_target->framebuffer(), f.width, f.height}, none, f.dt, shown_cut);
        put_picture(split_picture(magnified(read_framebuffer(plain_target->framebuffer(), f.width, f.height), zoom),
                                  magnified(read_framebuffer(f.target, f.width, f.height), zoom), zoom),
                    f.target);
      } else if (show == kTruth) {
        const ImageF truth = encode_srgb(supersampled(*plain, shown, f.width, f.height, s));
        ImageRGBA8 img = ImageRGBA8::blank(f.width, f.height);
        for (int y = 0; y < f.height; ++y)
          for (int x = 0; x < f.width; ++x) {
            for (int c = 0; c < 3; ++c) img.at(x, y)[c] = std::uint8_t(std::lround(255.f * truth.at(x, y, c)));
            img.at(x, y)[3] = 255;
          }
        put_picture(magnified(img, zoom), f.target);
      }
      app.metrics().set_allocation("the whole frame's targets (chapter 10)", frame.whole().allocated_bytes());
      app.metrics().set_allocation("motion RGBA32F x 2 + history RGBA16F x 2 + rejected R8 + box RGBA16F x 4 + AO/indirect RGBA32F + R32F x 2",
                                   frame.allocated_bytes() - frame.whole().allocated_bytes());
      if (std::ostream& out = app.report())
        out << "jitter (" << frame.last_jitter().x << ", " << frame.last_jitter().y << ") px, TAA " << (taa ? "on" : "off") << '\n';
      app.panel([&] {
        ImGui::Text("jitter %.3f, %.3f px", frame.last_jitter().x, frame.last_jitter().y);
        if (path_name != "off") ImGui::Text("path %s, frame %d", path_name.c_str(), (path_frame - 1));
      });
    }
    // 4. --strip: the kept frames side by side.
    if (!strip.empty()) {
      const int w = strip.front().width, h = strip.front().height;
      ImageRGBA8 all = ImageRGBA8::blank(w * int(strip.size()), h);
      for (std::size_t k = 0; k < strip.size(); ++k)
        for (int y = 0; y < h; ++y) std::copy_n(strip[k].at(0, y), std::size_t(w) * 4, all.at(int(k) * w, y));
      const std::string where = strip_path(app.options(), "11_temporal");
      save_png(where, all);
      std::cout << "wrote a strip of " << strip.size() << " frames: " << where << '\n';
      if (strip_full) std::cout << "note: the strip keeps the first " << kMaxStripFrames << " frames asked for\n";
    }
  });
}
