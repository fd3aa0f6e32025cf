// Chapter 10's whole frame on the GPU: every buffer follows a size change mid-run, and a stage
// switched off and on again gives back the first image (the frame is rebuilt from its plan).
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <utility>

#include "chapters/10_frame/whole_frame.h"
#include "common/paths.h"
#include "common/target.h"
#include "tests/unit/gl_environment.h"

using namespace lp;
using namespace lp::ch10;

namespace {

Scene shop_street() { return load_scene(from_root("assets/street_shop/street_shop.gltf")); }

// One image of the whole frame at w x h, as a new shot (the eye adaptation starts again).
ImageRGBA8 draw(WholeFrame& frame, const Scene& scene, int w, int h, const WholeFrameSettings& s = {}) {
  OutputTarget target(w, h);
  frame.render(frame_camera(scene.camera("shops"), float(w) / float(h)), {target.framebuffer(), w, h}, s, 1.f / 60.f, true);
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
  return target.read();
}

// The atrium with its tiled floor made glass of alpha 1 (the stage's "over" then writes the
// glass's own colour, nothing of what lies behind).
Scene atrium_with_glass_floor() {
  Scene s = load_scene(from_root("assets/atrium/atrium.gltf"));
  for (Material& m : s.materials)
    if (m.normal_texture >= 0) m.blend = true, m.base_color.a = 1.f;  // the floor: the one normal-mapped material
  return s;
}

// The whole frame's float radiance (before the HDR stage) of the atrium's aisle, a new shot.
ImageF radiance(WholeFrame& frame, const Scene& scene, const WholeFrameSettings& s) {
  const int w = 160, h = 90;
  OutputTarget target(w, h);
  frame.render(frame_camera(scene.camera("aisle"), float(w) / float(h)), {target.framebuffer(), w, h}, s, 1.f / 60.f, true);
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
  return frame.radiance()->read();
}

}  // namespace

// A window resized mid-run: the G-buffer, light and radiance targets, the light lists, the AO
// and indirect light's targets and the HDR chain all follow. The small frame equals a new whole
// frame's at that size, and back at the first size the image is the first one, byte for byte
// (every stage is deterministic: chapter 08's noise is a function of the pixel, not of time).
TEST(WholeFrameGl, ASizeChangeMidRunRebuildsEveryBuffer) {
  const Scene scene = shop_street();
  WholeFrame frame(scene);
  const ImageRGBA8 first = draw(frame, scene, 160, 90);
  const ImageRGBA8 small = draw(frame, scene, 96, 54);
  const ImageRGBA8 again = draw(frame, scene, 160, 90);
  WholeFrame fresh(scene);
  const ImageRGBA8 fresh_small = draw(fresh, scene, 96, 54);
  EXPECT_EQ(small.width, 96);
  EXPECT_TRUE(small.pixels == fresh_small.pixels) << compare(small, fresh_small).summary();
  EXPECT_TRUE(again.pixels == first.pixels) << compare(again, first).summary();
  // Not a blank frame: the street is lit, and the two sizes are different images.
  EXPECT_GT(compare(first, ImageRGBA8::blank(160, 90)).mean_error, 10.0);
}

// Each stage switched off, then on again: the frame rebuilds its stages from the plan, and the
// image with every stage on is the first one again. Each stage changes the image (the street
// has a sun, lights, tubes, ambient light and glass), so a knob that did nothing would fail.
TEST(WholeFrameGl, EachStageOffAndOnAgainGivesTheFirstImage) {
  const Scene scene = shop_street();
  WholeFrame frame(scene);
  const ImageRGBA8 all = draw(frame, scene, 160, 90);
  auto off = [](auto field) { WholeFrameSettings s; s.*field = false; return s; };
  for (auto [name, s] : {std::pair{"shadows", off(&WholeFrameSettings::shadows)},
                         std::pair{"clustered", off(&WholeFrameSettings::clustered)},
                         std::pair{"ao", off(&WholeFrameSettings::ao)},
                         std::pair{"indirect", off(&WholeFrameSettings::indirect)},
                         std::pair{"neon", off(&WholeFrameSettings::neon)}}) {
    SCOPED_TRACE(name);
    const ImageRGBA8 without = draw(frame, scene, 160, 90, s);
    if (std::string(name) != "clustered") { EXPECT_FALSE(without.pixels == all.pixels) << "switching it off changed nothing"; }
    const ImageRGBA8 back = draw(frame, scene, 160, 90);
    EXPECT_TRUE(back.pixels == all.pixels) << compare(back, all).summary();
  }
  WholeFrameSettings no_glass;
  no_glass.transparency = Method::Off;
  EXPECT_FALSE(draw(frame, scene, 160, 90, no_glass).pixels == all.pixels) << "the shop windows drew nothing";
}

// The whole frame follows chapter 06's marking: a sun marked casts_shadows: false gets no map,
// and the plan says why (the frame is then the same as with --shadows 0).
TEST(WholeFrameGl, ASunMarkedNotToCastShadowsGetsNoMap) {
  Scene scene = shop_street();
  WholeFrame marked_on(scene);
  ASSERT_TRUE(marked_on.plan({})[kShadowMap].runs);
  for (Light& l : scene.lights)
    if (l.type == LightType::Directional) l.casts_shadows = false;
  WholeFrame frame(scene);
  const PlannedStage shadow = frame.plan({})[kShadowMap];
  EXPECT_FALSE(shadow.runs);
  EXPECT_EQ(shadow.why, "no directional light that casts shadows");
  WholeFrameSettings no_shadows;
  no_shadows.shadows = false;
  EXPECT_TRUE(draw(frame, scene, 160, 90).pixels == draw(frame, scene, 160, 90, no_shadows).pixels);
}

// The glass reads the sun's shadow map on the units the frame gave chapter 06's stage, whatever
// ran between the lights and the glass: chapter 08's pass binds textures of its own there. The
// atrium's floor as glass of alpha 1 is lit by the sun (through its map), the local lights and
// the constant ambient, none of which chapter 08 computes: its radiance is the same, bit for
// bit, with AO and indirect light on or off. And the map is really read: without it the floor
// is brighter on the pixels the columns shade.
TEST(WholeFrameGl, TheGlassSeesTheSunsMapWithIndirectLightOnOrOff) {
  const Scene scene = atrium_with_glass_floor();
  WholeFrame frame(scene);
  WholeFrameSettings all, no_gi, no_glass, no_shadows;
  no_gi.ao = no_gi.indirect = false;
  no_glass.transparency = Method::Off;
  no_shadows.shadows = false;
  ASSERT_TRUE(frame.plan(all)[kShadowMap].runs && frame.plan(all)[kIndirect].runs && frame.plan(all)[kGlass].runs);
  const ImageF with_gi = radiance(frame, scene, all), without_gi = radiance(frame, scene, no_gi);
  const ImageF behind = radiance(frame, scene, no_glass), unshadowed = radiance(frame, scene, no_shadows);
  std::size_t floor = 0, same = 0, shaded = 0;
  for (std::size_t i = 0; i < with_gi.data.size(); i += 4) {  // RGBA floats
    auto rgb = [&](const ImageF& im) { return glm::vec3(im.data[i], im.data[i + 1], im.data[i + 2]); };
    if (rgb(with_gi) == rgb(behind)) continue;  // no glass here
    ++floor;
    if (rgb(with_gi) == rgb(without_gi)) ++same;
    if (glm::dot(rgb(with_gi), glm::vec3(1)) < 0.5f * glm::dot(rgb(unshadowed), glm::vec3(1))) ++shaded;
  }
  EXPECT_GT(floor, std::size_t(160 * 90 / 5)) << "the glass floor covers a fifth of the view at least";
  EXPECT_EQ(same, floor) << "glass pixels whose light changed with chapter 08's stage";
  EXPECT_GT(shaded, floor / 20) << "the sun's map darkens at least 5 % of the glass floor by half";
}

// Chapter 06's cascades for the sun in the whole frame (--sun-cascades, four by default): the
// default is four, the setting reaches the shadow stage (the street's image changes where the
// moon's shadows are drawn from four maps instead of one), and the image with cascades still has
// the moon's shadows (it is not the frame without them).
TEST(WholeFrameGl, SunCascadesReachTheShadowStage) {
  const Scene scene = shop_street();
  WholeFrame frame(scene);
  WholeFrameSettings one, four, none;
  EXPECT_EQ(four.sun_cascades, 4) << "the whole frame's sun: chapter 06's four cascades by default";
  one.sun_cascades = 1;
  none.shadows = false;
  const ImageRGBA8 a = draw(frame, scene, 160, 90, one), b = draw(frame, scene, 160, 90, four);
  const ImageRGBA8 c = draw(frame, scene, 160, 90, none);
  std::size_t differ = 0, differ_from_none = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) differ += a.pixels[i] != b.pixels[i], differ_from_none += b.pixels[i] != c.pixels[i];
  std::printf("four cascades against one map: %zu channel values differ; against no shadows: %zu\n", differ, differ_from_none);
  EXPECT_GT(differ, 0u);
  EXPECT_GT(differ_from_none, 0u);
  EXPECT_TRUE(draw(frame, scene, 160, 90, one).pixels == a.pixels);  // and back: the one map's image again
}
