// Chapter 11 without OpenGL: the Halton jitter, the camera paths and the motion picture's key.
#include <gtest/gtest.h>

#include <set>

#include "chapters/11_temporal/camera_path.h"
#include "chapters/11_temporal/jitter.h"
#include "chapters/11_temporal/motion_picture.h"
#include "common/error.h"
#include "common/paths.h"

using namespace lp;
using namespace lp::ch11;

// The radical inverse mirrors the digits: base 2: 1 -> 1/2, 6 = 110b -> 0.011b = 3/8;
// base 3: 5 = 12 (base 3) -> 0.21 (base 3) = 7/9.
TEST(Jitter, TheRadicalInverseMirrorsTheDigits) {
  EXPECT_FLOAT_EQ(radical_inverse(1, 2), 0.5f);
  EXPECT_FLOAT_EQ(radical_inverse(6, 2), 0.375f);
  EXPECT_FLOAT_EQ(radical_inverse(5, 3), 7.f / 9.f);
}

// Over a period the offsets average to zero (the history converges on the pixel's centre),
// stay inside the pixel, and are distinct. Derived: the first b^k - 1 points of base b are
// {1 .. b^k - 1} / b^k, mean exactly 1/2; period 8 in base 2 adds 1/16, mean 57/128, which the
// offsets subtract.
TEST(Jitter, HaltonJitterHasAZeroMeanOverItsPeriod) {
  EXPECT_FLOAT_EQ(halton_mean(7, 2), 0.5f);
  EXPECT_FLOAT_EQ(halton_mean(8, 3), 0.5f);
  EXPECT_FLOAT_EQ(halton_mean(8, 2), 57.f / 128.f);
  for (unsigned period : {1u, 4u, 8u, 16u}) {
    glm::vec2 sum(0);
    std::set<std::pair<float, float>> seen;
    for (unsigned i = 0; i < period; ++i) {
      const glm::vec2 o = jitter_offset(i, period);
      EXPECT_GE(o.x, -0.5f);
      EXPECT_LE(o.x, 0.5f);
      EXPECT_GE(o.y, -0.5f);
      EXPECT_LE(o.y, 0.5f);
      seen.insert({o.x, o.y});
      sum += o;
    }
    EXPECT_NEAR(sum.x / float(period), 0.f, 1e-6f) << "period " << period;
    EXPECT_NEAR(sum.y / float(period), 0.f, 1e-6f) << "period " << period;
    EXPECT_EQ(seen.size(), period);
    EXPECT_EQ(jitter_offset(period, period), jitter_offset(0, period));  // it repeats
  }
}

// A jittered projection moves every point's image by the offset, in pixels.
TEST(Jitter, TheJitteredProjectionMovesTheImageByTheOffset) {
  FrameCamera c;
  c.projection = glm::perspective(0.8f, 16.f / 9.f, 0.1f, 100.f);
  const FrameCamera j = jittered(c, {0.25f, -0.5f}, 160, 90);
  for (const glm::vec4 p : {glm::vec4(0, 0, -5, 1), glm::vec4(3, -1, -40, 1)}) {
    const glm::vec4 a = c.projection * p, b = j.projection * p;
    EXPECT_NEAR((b.x / b.w - a.x / a.w) * 0.5f * 160.f, 0.25f, 1e-4f);
    EXPECT_NEAR((b.y / b.w - a.y / a.w) * 0.5f * 90.f, -0.5f, 1e-4f);
    EXPECT_FLOAT_EQ(b.z / b.w, a.z / a.w);  // depth untouched
  }
}

// The paths: frame 0 is the named view, the frame count is the duration at the rate, a cut is
// reported on the frame it happens and on no other, and unknown names say what there is.
TEST(CameraPaths, FramesPosesAndCuts) {
  const std::string street = "assets/street_shop/street_shop.gltf";
  const Scene scene = load_scene(from_root(street));
  const CameraPath& walk = path_named(street, "walk");
  EXPECT_EQ(walk.frames(), 91);  // 3 s at 30 frames a second, both ends
  const Camera first = walk.camera(scene, 0);
  EXPECT_EQ(first.world, scene.camera("shops").world);
  EXPECT_NE(walk.camera(scene, 45).world, first.world);
  EXPECT_EQ(walk.camera(scene, 45).world, walk.camera(scene, 45).world);  // deterministic
  int walk_cuts = 0;
  for (int i = 1; i < walk.frames(); ++i) walk_cuts += walk.cut_at(i);
  EXPECT_EQ(walk_cuts, 0);
  EXPECT_TRUE(walk.cut_at(0));
  const CameraPath& cut = path_named(street, "cut");
  std::vector<int> cuts;
  for (int i = 1; i < cut.frames(); ++i)
    if (cut.cut_at(i)) cuts.push_back(i);
  ASSERT_EQ(cuts, std::vector<int>{30});  // the frame at t = 1 s shows the new view
  EXPECT_EQ(glm::vec3(cut.camera(scene, 30).world[3]), scene.camera("shop_window").position());
  try {
    path_named(street, "fly");
    FAIL() << "no error for an unknown path";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("walk"), std::string::npos) << e.what();
  }
}

// --show motion's key says what its picture shows: a field moving up the screen (GL's +y) at half
// the full scale has the colour of the key's disc half way up from its centre, one moving right
// at full scale that of its rim on the right; the two differ, and a still pixel is black.
TEST(MotionPicture, TheKeysWheelHasThePicturesColourForEachDirectionAndLength) {
  const int w = 64, h = 32;
  const float full = 8.f;
  auto field = [&](float dx_px, float dy_px) {  // RGBA32F as read back: xy in uv units
    std::vector<float> m(std::size_t(w) * h * 4, 0.f);
    for (std::size_t i = 0; i < m.size(); i += 4) m[i] = dx_px / float(w), m[i + 1] = dy_px / float(h);
    return motion_picture(m, w, h, full);
  };
  lp::ImageRGBA8 key_image = lp::ImageRGBA8::blank(320, 180);
  const lp::DirectionKeyPlace k = lp::draw_direction_key(key_image, motion_key(full));
  ASSERT_EQ(k.radius % 2, 0) << "half the radius is a whole pixel";
  auto same = [](const std::uint8_t* a, const std::uint8_t* b) { return a[0] == b[0] && a[1] == b[1] && a[2] == b[2]; };
  const lp::ImageRGBA8 up = field(0, full / 2);
  const lp::ImageRGBA8 right = field(full, 0);
  const std::uint8_t* key_up = key_image.at(k.centre_x, k.centre_y - k.radius / 2);
  const std::uint8_t* key_right = key_image.at(k.centre_x + k.radius, k.centre_y);
  EXPECT_TRUE(same(up.at(5, 5), key_up)) << "up: picture " << int(up.at(5, 5)[0]) << "," << int(up.at(5, 5)[1]) << ","
                                          << int(up.at(5, 5)[2]) << " key " << int(key_up[0]) << "," << int(key_up[1]) << "," << int(key_up[2]);
  EXPECT_TRUE(same(right.at(5, 5), key_right));
  EXPECT_FALSE(same(up.at(5, 5), right.at(5, 5)));
  EXPECT_FALSE(same(up.at(5, 5), field(0, full).at(5, 5))) << "half the scale is not full colour";
  const lp::ImageRGBA8 still = field(0, 0);
  EXPECT_EQ(still.at(5, 5)[0] + still.at(5, 5)[1] + still.at(5, 5)[2], 0);
  EXPECT_THROW(motion_picture(std::vector<float>(10), w, h, full), lp::Error);
}

// --show rejected's key lies inside the picture at the exercises' 160x90 (its short words) and at
// the references' 320x180 (its full ones): its box, and every pixel it draws.
TEST(RejectedKey, ItsTextLiesInsideThePictureAt160x90) {
  for (auto [w, h] : {std::pair{160, 90}, std::pair{320, 180}}) {
    ImageRGBA8 image = ImageRGBA8::blank(w, h);
    const LegendPlace p = draw_legend(image, ch11::rejected_key());
    ASSERT_GT(p.width * p.height, 0) << w << 'x' << h << ": the key is drawn";
    EXPECT_GE(p.x, 0);
    EXPECT_LE(p.x + p.width, w) << w << 'x' << h;
    EXPECT_LE(p.y + p.height, h) << w << 'x' << h;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        if (x >= p.x + p.width || y < p.y) {
          ASSERT_EQ(image.at(x, y)[3], 0) << w << 'x' << h << ": drawn at " << x << ',' << y;
        }
    // The words end inside the box (its right margin is only box): none cut at the picture's edge.
    for (int y = p.y; y < p.y + p.height; ++y) ASSERT_EQ(image.at(p.x + p.width - 1, y)[0], 24) << w << 'x' << h << ": text at the box's edge, row " << y;
  }
}
