// Chapter 04's scene description: neon lights from glTF node extras.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "chapters/04_neon/neon_scene.h"
#include "common/error.h"
#include "common/paths.h"

using namespace lp;
using namespace lp::ch04;

TEST(NeonScene, ParsesADescriptionOnARotatedNode) {
  // A node at (1, 2, 3) turned 90 degrees about Z: its local X (the tube) points along +Y.
  glm::mat4 world = glm::translate(glm::mat4(1), {1, 2, 3}) * glm::rotate(glm::mat4(1), glm::radians(90.f), {0, 0, 1});
  NeonLight l = parse_neon("sign", world, R"({"neon": {"length": 2, "intensity": 1.5, "color": [1, 0.5, 0.25],
      "radius": 0.03, "specular": 0.5, "caps": false, "barn_doors": [0.2, 2, 0.3, 1.5]}})");
  EXPECT_EQ(l.name, "sign");
  EXPECT_NEAR(glm::length(l.start - glm::vec3(1, 1, 3)), 0.f, 1e-6f);
  EXPECT_NEAR(glm::length(l.end - glm::vec3(1, 3, 3)), 0.f, 1e-6f);
  EXPECT_NEAR(glm::length(l.door_axis - glm::vec3(-1, 0, 0)), 0.f, 1e-6f);  // local +Y turned
  EXPECT_EQ(l.intensity, 1.5f);
  EXPECT_EQ(l.color, glm::vec3(1, 0.5f, 0.25f));
  EXPECT_EQ(l.radius, 0.03f);
  EXPECT_EQ(l.specular, 0.5f);
  EXPECT_FALSE(l.caps);
  EXPECT_EQ(l.barn_doors.count, 2.f);
  EXPECT_EQ(l.barn_doors.softness, 1.5f);
}

TEST(NeonScene, DefaultsAndZeroLength) {
  NeonLight l = parse_neon("dot", glm::mat4(1), R"({"neon": {"length": 0, "intensity": 1}})");
  EXPECT_EQ(l.start, l.end);
  EXPECT_EQ(l.color, glm::vec3(1));
  EXPECT_TRUE(l.caps);
  EXPECT_FALSE(l.barn_doors.enabled());
  EXPECT_EQ(l.specular, 1.f);
}

TEST(NeonScene, MalformedDescriptionsNameTheNode) {
  const char* bad[] = {
      R"({"neon": {"intensity": 1}})",                          // no length
      R"({"neon": {"length": 1}})",                             // no intensity
      R"({"neon": {"length": -1, "intensity": 1}})",            // negative length
      R"({"neon": {"length": 1, "intensity": 0}})",             // no light
      R"({"neon": {"length": 1, "intensity": 1, "color": [1, 0]}})",
      R"({"neon": {"length": 1, "intensity": 1, "radius": 0}})",
      R"({"neon": {"length": "long", "intensity": 1}})",
      R"({"neon": {"length": 1, "intensity": 1, "caps": 1}})",
      R"({"neon": {"length": 1, "intensity": 1, "barn_doors": [1, 2]}})",
      R"({"neon": 3})",
  };
  for (const char* json : bad) {
    try {
      parse_neon("broken_sign", glm::mat4(1), json);
      ADD_FAILURE() << "accepted " << json;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("neon light 'broken_sign'"), std::string::npos) << e.what();
    }
  }
}

TEST(NeonScene, LoadsTheChaptersScene) {
  Scene scene = load_scene(from_root("assets/neon/neon.gltf"));
  std::vector<NeonLight> tubes = neon_lights(scene);
  ASSERT_EQ(tubes.size(), 3u);
  EXPECT_EQ(tubes[0].name, "neon_pink");
  EXPECT_EQ(tubes[1].name, "neon_cyan");
  EXPECT_EQ(tubes[2].name, "neon_amber");
  // The pink tube lies along +X in front of the wall (z = -2), parallel to it.
  EXPECT_NEAR(tubes[0].start.z, -1.7f, 1e-5f);
  EXPECT_NEAR(tubes[0].end.z, -1.7f, 1e-5f);
  EXPECT_NEAR(tubes[0].length(), 2.4f, 1e-5f);
  // The cyan tube leans with its lower end touching the floor: 3 cm, its radius.
  EXPECT_NEAR(std::min(tubes[1].start.y, tubes[1].end.y), tubes[1].radius, 1e-5f);
  EXPECT_FALSE(tubes[2].caps);
  EXPECT_TRUE(tubes[2].barn_doors.enabled());
  EXPECT_EQ(scene.lights.size(), 1u);  // and one ordinary light, the moon
}

TEST(NeonScene, OtherScenesHaveNoNeonButKeepTheirExtras) {
  Scene scene = load_scene(from_root("assets/forward/forward.gltf"));
  EXPECT_TRUE(neon_lights(scene).empty());
  // The analytic shapes' extras are kept as JSON too (and still read as shapes).
  ASSERT_FALSE(scene.node_extras.empty());
  EXPECT_NE(scene.node_extras.front().lightpass_json.find("shape"), std::string::npos);
}
