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
    if (std::string(name) != "clustered") EXPECT_FALSE(without.pixels == all.pixels) << "switching it off changed nothing";
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
