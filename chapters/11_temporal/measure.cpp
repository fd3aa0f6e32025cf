#include "chapters/11_temporal/measure.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

#include "chapters/07_ssao/ao_truth.h"
#include "chapters/06_shadows/shadow_truth.h"
#include "chapters/08_ssgi/gi_truth.h"
#include "common/error.h"
#include "common/target.h"

namespace lp::ch11 {

ImageF read_texture_rgba(GLuint texture, int width, int height) {
  ImageF rows = ImageF::blank(width, height, 4);
  glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, GLsizei(rows.data.size() * sizeof(float)), rows.data.data());
  flip_vertically(rows);  // GL's rows are bottom first
  return rows;
}

ImageF encode_srgb(const ImageF& linear) {
  ImageF out = ImageF::blank(linear.width, linear.height, 3);
  for (int y = 0; y < linear.height; ++y)
    for (int x = 0; x < linear.width; ++x)
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = linear_to_srgb(std::clamp(linear.at(x, y, c), 0.f, 1.f));
  return out;
}

namespace {
// to_srgb8 encodes linear values: the measured images are sRGB-encoded already.
ImageF decode_srgb_for_png(const ImageF& encoded) {
  ImageF out = encoded;
  for (float& v : out.data) v = srgb_to_linear(v);
  return out;
}
}  // namespace

// [disocclusion-twin-body]
std::vector<std::uint8_t> disocclusion_mask(const ImageF& now, const ImageF& then, float tolerance, float slope,
                                            std::vector<float>* margin) {
  const int w = now.width, h = now.height;
  std::vector<std::uint8_t> mask(std::size_t(w) * h, 0);
  if (margin) margin->assign(mask.size(), std::numeric_limits<float>::infinity());
  auto z = [&](int x, int y) { return now.at(std::clamp(x, 0, w - 1), std::clamp(y, 0, h - 1), 2); };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      // Rows top first here; the motion's uv has v up.
      const float u = (float(x) + 0.5f) / float(w) - now.at(x, y, 0);
      const float v = 1.f - (float(y) + 0.5f) / float(h) - now.at(x, y, 1);  // uv then = uv now - motion
      const float depth_then = now.at(x, y, 2);
      bool hidden = u < 0.f || u > 1.f || v < 0.f || v > 1.f;
      if (!hidden) {
        const int bx = int(std::floor(u * float(w) - 0.5f)), by = int(std::floor(v * float(h) - 0.5f));
        float nearest = 1e30f;
        for (int j = 0; j <= 1; ++j)
          for (int i = 0; i <= 1; ++i) {
            const int qx = std::clamp(bx + i, 0, w - 1), qy = std::clamp(by + j, 0, h - 1);
            nearest = std::min(nearest, std::abs(then.at(qx, h - 1 - qy, 3) - depth_then));
          }
        const float dx = std::min(std::abs(z(x + 1, y) - depth_then), std::abs(depth_then - z(x - 1, y)));
        const float dy = std::min(std::abs(z(x, y - 1) - depth_then), std::abs(depth_then - z(x, y + 1)));
        const float threshold = tolerance * depth_then + slope * (dx + dy);
        hidden = nearest > threshold;
        if (margin) (*margin)[std::size_t(y) * w + x] = (nearest - threshold) / depth_then;
      }
      mask[std::size_t(y) * w + x] = hidden ? 1 : 0;
    }
  return mask;
}
// [/disocclusion-twin-body]

std::vector<std::uint8_t> edge_mask(const ImageF& truth, float range) {
  const int w = truth.width, h = truth.height;
  auto luma = [&](int x, int y) {
    x = std::clamp(x, 0, w - 1);
    y = std::clamp(y, 0, h - 1);
    return 0.2126f * truth.at(x, y, 0) + 0.7152f * truth.at(x, y, 1) + 0.0722f * truth.at(x, y, 2);
  };
  std::vector<std::uint8_t> mask(std::size_t(w) * h, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float lo = 1e30f, hi = -1e30f;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const float l = luma(x + dx, y + dy);
          lo = std::min(lo, l);
          hi = std::max(hi, l);
        }
      mask[std::size_t(y) * w + x] = hi - lo > range ? 1 : 0;
    }
  return mask;
}

double mean_error(const ImageF& image, const ImageF& truth, const std::vector<std::uint8_t>& mask, std::size_t* pixels) {
  if (image.width != truth.width || image.height != truth.height) throw Error("mean_error: images of different sizes");
  double sum = 0;
  std::size_t n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      if (!mask.empty() && !mask[std::size_t(y) * image.width + x]) continue;
      double e = 0;
      for (int c = 0; c < 3; ++c) e += std::abs(double(image.at(x, y, c)) - double(truth.at(x, y, c)));
      sum += e / 3.0;
      ++n;
    }
  if (pixels) *pixels = n;
  return n ? sum / double(n) : 0.0;
}

// [measure-path]
std::vector<PathFrame> measure_path(const SceneGpu& scene, const CameraPath& path, const TemporalSettings& settings,
                                    const PathRunOptions& o) {
  const int w = o.width, h = o.height;
  if (w < 1 || h < 1 || w > 4096 || h > 4096) throw Error("measure_path: a size of " + std::to_string(w) + "x" + std::to_string(h));
  const int end = o.count < 0 ? path.frames() : std::min(path.frames(), o.first + o.count);
  TemporalFrame frame(scene), truth_frame(scene);
  OutputTarget target(w, h);
  // The motion pass runs for every variant, so ghosting and convergence count the same pixels
  // with and without TAA (it writes only its own targets: the image does not change).
  TemporalSettings measured = settings;
  measured.motion_alone = true;
  TemporalSettings truth_settings = settings;
  truth_settings.taa.enabled = false;
  std::vector<PathFrame> out;
  std::vector<int> since_disocclusion(std::size_t(w) * h, 1 << 20);  // frames since each pixel was hidden
  ImageF last_image, last_truth, last_motion;
  auto truth_of = [&](int i, const auto& compute) {
    if (o.truths && std::size_t(i) < o.truths->size() && (*o.truths)[std::size_t(i)].width == w) return (*o.truths)[std::size_t(i)];
    std::string file;
    if (!o.truth_dir.empty()) {
      // Named by path, size, grid and frame; the caller clears the folder when the scene or
      // the frame's settings change.
      char n[64];
      std::snprintf(n, sizeof n, "_%dx%d_grid%d_%03d.pfm", w, h, o.truth_grid, i);
      file = o.truth_dir + "/truth_" + path.scene + "_" + path.name + n;
    }
    ImageF t = !file.empty() && std::filesystem::exists(file) ? load_pfm(file) : compute();
    if (!file.empty() && !std::filesystem::exists(file)) save_pfm(file, t);
    if (o.truths) {
      if (o.truths->size() <= std::size_t(i)) o.truths->resize(std::size_t(i) + 1);
      (*o.truths)[std::size_t(i)] = t;
    }
    return t;
  };
  for (int i = 0; i < end; ++i) {
    const FrameCamera camera = frame_camera(path.camera(scene.scene(), i), float(w) / float(h));
    const bool cut = path.cut_at(i);
    frame.render(camera, {target.framebuffer(), w, h}, measured, 1.f / path.fps, cut);
    // Disocclusion from the motion alone (the C++ twin), whatever the resolve did with it.
    const ImageF motion = read_texture_rgba(frame.motion().current(), w, h);
    std::vector<std::uint8_t> hidden;
    if (!cut && last_motion.width == w) hidden = disocclusion_mask(motion, last_motion, o.disocclusion_tolerance, o.disocclusion_slope);
    for (std::size_t k = 0; k < since_disocclusion.size(); ++k)
      since_disocclusion[k] = cut ? (1 << 20) : hidden.empty() ? since_disocclusion[k] + 1 : hidden[k] ? 0 : since_disocclusion[k] + 1;
    last_motion = motion;
    if (i < o.first) continue;
    const ImageF image = encode_srgb(read_linear(target.framebuffer(), w, h));
    const ImageF truth = truth_of(i, [&] { return encode_srgb(supersampled(truth_frame, camera, w, h, truth_settings, o.truth_grid)); });
    PathFrame f{.frame = i, .cut = cut};
    if (!o.dump_prefix.empty()) {
      char n[16];
      std::snprintf(n, sizeof n, "%03d", i);
      save_png(o.dump_prefix + n + "_image.png", to_srgb8(decode_srgb_for_png(image)));
      save_png(o.dump_prefix + n + "_truth.png", to_srgb8(decode_srgb_for_png(truth)));
    }
    f.error = mean_error(image, truth);
    f.edge_error = mean_error(image, truth, edge_mask(truth), &f.edge_pixels);
    std::vector<std::uint8_t> ghost(since_disocclusion.size());
    for (std::size_t k = 0; k < ghost.size(); ++k) ghost[k] = since_disocclusion[k] < o.ghost_frames ? 1 : 0;
    f.ghost_error = mean_error(image, truth, ghost, &f.ghost_pixels);
    const int bins = std::max(1, o.ghost_frames * 2);
    f.since_error.resize(std::size_t(bins));
    f.since_pixels.resize(std::size_t(bins));
    for (int k = 0; k < bins; ++k) {
      for (std::size_t q = 0; q < ghost.size(); ++q) ghost[q] = since_disocclusion[q] == k ? 1 : 0;
      f.since_error[std::size_t(k)] = mean_error(image, truth, ghost, &f.since_pixels[std::size_t(k)]);
    }
    if (!cut && last_truth.width == w) {
      std::vector<std::uint8_t> still(std::size_t(w) * h, 0);
      std::vector<std::uint8_t> all(std::size_t(w) * h, 1);
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          float change = 0;
          for (int c = 0; c < 3; ++c) change = std::max(change, std::abs(truth.at(x, y, c) - last_truth.at(x, y, c)));
          still[std::size_t(y) * w + x] = change < o.still_change ? 1 : 0;
        }
      f.flicker = mean_error(image, last_image, still, &f.still_pixels);
    }
    last_image = image;
    last_truth = truth;
    out.push_back(f);
  }
  return out;
}
// [/measure-path]

namespace {
// Plays `path` frame by frame up to `end` on `frame`, whose stages include `motion`: `before(i,
// camera, cut, k)` sets this frame's stages (k: frames since the last cut), the frame is drawn,
// the frames since each pixel was last disoccluded are counted (the C++ twin's test on this
// frame's motion and the last's; a cut sets every pixel far back), and from `first` on
// `after(i, camera, since)` measures it.
template <class Before, class After>
void play_path(const SceneGpu& scene, const CameraPath& path, ch03::DeferredFrame& frame, MotionStage& motion, int w,
               int h, int first, int end, float tolerance, float slope, Before before, After after) {
  OutputTarget target(w, h);
  std::vector<int> since(std::size_t(w) * h, 1 << 20);
  ImageF last_motion;
  FrameCamera last;
  int start = 0;  // the last cut's frame
  for (int i = 0; i < end; ++i) {
    const FrameCamera camera = frame_camera(path.camera(scene.scene(), i), float(w) / float(h));
    const bool cut = i == 0 || path.cut_at(i);
    if (cut) start = i;
    before(i, camera, cut, unsigned(i - start));
    motion.set_cameras(camera, cut ? camera : last);
    frame.render(camera, {target.framebuffer(), w, h});
    last = camera;
    const ImageF m = read_texture_rgba(motion.current(), w, h);
    std::vector<std::uint8_t> hidden;
    if (!cut && last_motion.width == w) hidden = disocclusion_mask(m, last_motion, tolerance, slope);
    for (std::size_t k = 0; k < since.size(); ++k)
      since[k] = cut ? (1 << 20) : hidden.empty() ? since[k] + 1 : hidden[k] ? 0 : since[k] + 1;
    last_motion = m;
    if (i >= first) after(i, camera, since);
  }
}

// The mean of `error(x, y)` (negative: not counted) over the pixels disoccluded exactly k frames
// ago, k = 0 .. bins - 1, and how many.
template <class PixelError>
void bin_by_since(const std::vector<int>& since, int w, int h, int bins, PixelError error, std::vector<double>& mean,
                  std::vector<std::size_t>& pixels) {
  mean.assign(std::size_t(bins), 0.0);
  pixels.assign(std::size_t(bins), 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int k = since[std::size_t(y) * w + x];
      if (k >= bins) continue;
      const double e = error(x, y);
      if (e < 0.0) continue;
      mean[std::size_t(k)] += e;
      ++pixels[std::size_t(k)];
    }
  for (int k = 0; k < bins; ++k)
    if (pixels[std::size_t(k)]) mean[std::size_t(k)] /= double(pixels[std::size_t(k)]);
}
}  // namespace

// [measure-ao-path]
std::vector<AoPathFrame> measure_ao_path(const SceneGpu& scene, const CameraPath& path, const ch07::AoSettings& settings,
                                         const TemporalAoSettings& temporal, const AoPathOptions& o) {
  const int w = o.width, h = o.height;
  if (w < 1 || h < 1 || w > 4096 || h > 4096) throw Error("measure_ao_path: a size of " + std::to_string(w) + "x" + std::to_string(h));
  if (o.bins < 1 || o.bins > 1024) throw Error("measure_ao_path: bins must be 1 to 1024");
  const int end = o.count < 0 ? path.frames() : std::min(path.frames(), o.first + o.count);
  ch03::DeferredFrame frame(scene);
  ch07::AoStage ao;
  MotionStage motion(scene);
  TemporalAoStage accumulated(ao, motion);
  frame.add_stage(ao);
  frame.add_stage(motion);
  frame.add_stage(accumulated);
  accumulated.set(temporal);
  std::vector<AoPathFrame> out;
  auto before = [&](int, const FrameCamera&, bool cut, unsigned k) {
    ao.set(frame_ao(settings, temporal, k), ch07::AoShow::Ao, glm::vec3(1.f));  // shown: the pass runs whatever the scene's ambient
    if (cut) accumulated.reset();
  };
  auto after = [&](int i, const FrameCamera& camera, const std::vector<int>& since) {
    const ImageF a = ao.ssao().read_full(w, h);
    const ImageF truth = ch07::cached_ray_traced_ao(scene.scene(), camera, w, h, {.radius = settings.radius, .samples = o.truth_samples});
    AoPathFrame f{.frame = i, .error = ch07::ao_errors(a, truth).mean_abs, .ao = a};
    bin_by_since(since, w, h, o.bins, [&](int x, int y) {
      return truth.at(x, y, 0) < 0.f ? -1.0 : std::abs(double(a.at(x, y, 0)) - truth.at(x, y, 0));
    }, f.since_error, f.since_pixels);
    out.push_back(f);
  };
  play_path(scene, path, frame, motion, w, h, o.first, end, temporal.depth_tolerance, temporal.depth_slope, before, after);
  return out;
}
// [/measure-ao-path]

// [measure-gi-path]
std::vector<GiPathFrame> measure_gi_path(const SceneGpu& scene, const CameraPath& path, const ch08::GiSettings& settings,
                                         const TemporalGiSettings& temporal, const GiPathOptions& o) {
  const int w = o.width, h = o.height;
  if (w < 1 || h < 1 || w > 4096 || h > 4096) throw Error("measure_gi_path: a size of " + std::to_string(w) + "x" + std::to_string(h));
  if (o.bins < 1 || o.bins > 1024) throw Error("measure_gi_path: bins must be 1 to 1024");
  const int end = o.count < 0 ? path.frames() : std::min(path.frames(), o.first + o.count);
  ch03::DeferredFrame frame(scene);
  ch03::use_lights(frame, scene.scene(), scene.scene().lights, false);
  ch08::GiStage gi(scene);
  MotionStage motion(scene);
  TemporalGiStage accumulated(motion);
  gi.set_filter(&accumulated);
  frame.add_stage(gi);
  frame.add_stage(motion);
  accumulated.set(temporal);
  std::vector<GiPathFrame> out;
  auto before = [&](int, const FrameCamera&, bool cut, unsigned k) {
    gi.set(ch08::GiMode::Ssgi, frame_gi(settings, temporal, k), ch08::GiShow::Image, scene.scene().ambient);
    if (cut) accumulated.reset();
  };
  auto after = [&](int i, const FrameCamera& camera, const std::vector<int>& since) {
    GiPathFrame f{.frame = i, .gi = gi.ssgi().read()};
    if (gi.ssgi().transfer()) {
      f.transfer = ImageF::blank(w, h, 1);
      glGetTextureImage(gi.ssgi().transfer(), 0, GL_RED, GL_FLOAT, GLsizei(f.transfer.data.size() * sizeof(float)),
                        f.transfer.data.data());
      flip_vertically(f.transfer);
    }
    if (o.truth_samples <= 0) {  // the pass's results alone
      out.push_back(f);
      return;
    }
    const ImageF truth = ch08::cached_ray_traced_indirect(scene.scene(), frame.volumes().lights(), camera, w, h,
                                                          {.samples = o.truth_samples, .screen_limited = o.screen_limited});
    f.error = ch08::gi_errors(f.gi, truth).mean_abs;
    if (o.ao_truth) {
      ImageF a = ImageF::blank(w, h, 1);
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) a.at(x, y, 0) = f.gi.at(x, y, 3);
      f.ao_error = ch07::ao_errors(a, ch07::cached_ray_traced_ao(scene.scene(), camera, w, h,
                                                                 {.radius = settings.ao_radius, .samples = o.truth_samples}))
                       .mean_abs;
    }
    bin_by_since(since, w, h, o.bins, [&](int x, int y) {
      if (truth.at(x, y, 0) < 0.f) return -1.0;
      double e = 0;
      for (int c = 0; c < 3; ++c) e += std::abs(double(f.gi.at(x, y, c)) - truth.at(x, y, c));
      return e / 3.0;
    }, f.since_error, f.since_pixels);
    out.push_back(f);
  };
  play_path(scene, path, frame, motion, w, h, o.first, end, temporal.depth_tolerance, temporal.depth_slope, before, after);
  return out;
}
// [/measure-gi-path]

// [measure-shadow-path]
std::vector<ShadowPathFrame> measure_shadow_path(const SceneGpu& scene, const CameraPath& path,
                                                 const ch06::ShadowSettings& settings,
                                                 const TemporalShadowSettings& temporal, const ShadowPathOptions& o) {
  const int w = o.width, h = o.height;
  if (w < 1 || h < 1 || w > 4096 || h > 4096)
    throw Error("measure_shadow_path: a size of " + std::to_string(w) + "x" + std::to_string(h));
  if (o.bins < 1 || o.bins > 1024) throw Error("measure_shadow_path: bins must be 1 to 1024");
  const int sun = ch06::shadowed_sun(scene.scene());
  if (sun < 0) throw Error("measure_shadow_path: the scene has no sun that casts shadows");
  const int end = o.count < 0 ? path.frames() : std::min(path.frames(), o.first + o.count);
  ch03::DeferredFrame frame(scene);
  ch03::use_lights(frame, scene.scene(), scene.scene().lights, false);
  ch06::ShadowStage shadows(scene, scene.scene().lights[std::size_t(sun)]);
  MotionStage motion(scene);
  TemporalShadowStage accumulated([&] { return &shadows; }, motion);
  frame.add_stage(shadows);
  frame.add_stage(motion);
  frame.add_stage(accumulated);
  accumulated.set(temporal);
  std::unique_ptr<RayScene> rays;
  std::vector<ShadowPathFrame> out;
  auto before = [&](int, const FrameCamera&, bool cut, unsigned k) {
    shadows.set(frame_shadows(settings, temporal, k));
    if (cut) accumulated.reset();
  };
  auto after = [&](int i, const FrameCamera& camera, const std::vector<int>& since) {
    ShadowPathFrame f{.frame = i, .visibility = ImageF::blank(w, h, 1), .radius = ImageF::blank(w, h, 1)};
    for (auto [texture, image] : {std::pair{accumulated.visibility(), &f.visibility}, {accumulated.radius(), &f.radius}}) {
      glGetTextureImage(texture, 0, GL_RED, GL_FLOAT, GLsizei(image->data.size() * sizeof(float)), image->data.data());
      flip_vertically(*image);
    }
    if (o.truth_samples <= 0) {
      out.push_back(f);
      return;
    }
    if (!rays) rays = std::make_unique<RayScene>(scene.scene());
    const ImageF truth = ch06::cached_shadow_truth(scene.scene(), *rays, camera, w, h, shadows.sun().direction,
                                                   {.angular_radius = settings.sun_angular_radius, .samples = o.truth_samples});
    f.error = ch06::visibility_error(f.visibility, truth, 1).mean_abs;
    bin_by_since(since, w, h, o.bins, [&](int x, int y) {
      return truth.at(x, y, 2) < 0.5f ? -1.0 : std::abs(double(f.visibility.at(x, y, 0)) - truth.at(x, y, 1));
    }, f.since_error, f.since_pixels);
    out.push_back(f);
  };
  play_path(scene, path, frame, motion, w, h, o.first, end, temporal.depth_tolerance, temporal.depth_slope, before, after);
  return out;
}
// [/measure-shadow-path]

}  // namespace lp::ch11
