// glTF loading: our scenes load cleanly; bad files give errors that say what and where;
// missing data is generated or replaced with a warning.
#include <gtest/gtest.h>

#include "common/error.h"
#include "common/paths.h"
#include "common/scene.h"

using namespace lp;

namespace {
std::string load_error(const std::string& file) {
  try {
    load_scene(from_root("tests/data/" + file));
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}
}  // namespace

TEST(Scene, BookScenesLoadWithoutWarnings) {
  for (const char* name : {"forward", "atrium", "street", "cornell"}) {
    Scene s = load_scene(from_root(std::string("assets/") + name + "/" + name + ".gltf"));
    EXPECT_TRUE(s.warnings.empty()) << name << ": " << (s.warnings.empty() ? "" : s.warnings.front());
    EXPECT_FALSE(s.cameras.empty()) << name;
    EXPECT_FALSE(s.lights.empty()) << name;
    EXPECT_FALSE(s.instances.empty()) << name;
    for (const auto& v : s.vertices) {
      ASSERT_NEAR(glm::length(v.normal), 1.f, 1e-3f) << name;
      ASSERT_NEAR(glm::length(glm::vec3(v.tangent)), 1.f, 1e-3f) << name;
      ASSERT_NEAR(glm::dot(v.normal, glm::vec3(v.tangent)), 0.f, 2e-2f) << name;
    }
  }
}

TEST(Scene, ForwardSceneHasTheChapterViewsAndExactShapes) {
  Scene s = load_scene(from_root("assets/forward/forward.gltf"));
  for (const char* view : {"overview", "close_8", "close_16", "close_32", "close_64", "close_128", "grazing"})
    EXPECT_NO_THROW(s.camera(view)) << view;
  int spheres = 0;
  for (const auto& i : s.instances) spheres += i.shape.kind == Shape::Sphere;
  EXPECT_EQ(spheres, 5);
  bool has_point = false, has_spot = false, has_directional = false;
  for (const auto& l : s.lights) {
    has_point |= l.type == LightType::Point;
    has_spot |= l.type == LightType::Spot;
    has_directional |= l.type == LightType::Directional;
  }
  EXPECT_TRUE(has_point && has_spot && has_directional);
}

TEST(Scene, UnknownViewListsTheViews) {
  Scene s = load_scene(from_root("assets/forward/forward.gltf"));
  try {
    s.camera("nope");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("overview"), std::string::npos) << e.what();
  }
}

TEST(Scene, MissingFile) {
  EXPECT_NE(load_error("does_not_exist.gltf").find("no such file"), std::string::npos);
  EXPECT_NE(load_error("does_not_exist.gltf").find("tests/data/does_not_exist.gltf"), std::string::npos);
}

TEST(Scene, EmptyFile) { EXPECT_NE(load_error("empty_file.gltf").find("empty"), std::string::npos); }

TEST(Scene, MalformedJsonNamesTheFile) {
  std::string e = load_error("malformed.gltf");
  EXPECT_NE(e.find("malformed.gltf"), std::string::npos) << e;
  EXPECT_EQ(e.find("(no error)"), std::string::npos) << e;
}

TEST(Scene, MissingBufferNamesTheFile) {
  std::string e = load_error("missing_buffer.gltf");
  EXPECT_NE(e.find("missing_buffer"), std::string::npos) << e;
  EXPECT_EQ(e.find("(no error)"), std::string::npos) << e;
}

TEST(Scene, IndexPastTheVerticesIsAnError) {
  std::string e = load_error("bad_index.gltf");
  EXPECT_NE(e.find("past the"), std::string::npos) << e;
}

TEST(Scene, MissingTextureFallsBackWithAWarning) {
  Scene s = load_scene(from_root("tests/data/missing_texture.gltf"));
  ASSERT_FALSE(s.warnings.empty());
  EXPECT_NE(s.warnings.front().find("could not be loaded"), std::string::npos) << s.warnings.front();
  ASSERT_FALSE(s.textures.empty());
  EXPECT_TRUE(s.textures.front().fallback);
  EXPECT_GT(s.textures.front().image.width, 0);
}

TEST(Scene, NonIndexedMeshWithoutNormalsGetsThemGenerated) {
  Scene s = load_scene(from_root("tests/data/nonindexed_nonormals.gltf"));
  ASSERT_FALSE(s.instances.empty());
  glm::vec3 centre = (s.bounds_min + s.bounds_max) * 0.5f;
  const Instance& inst = s.instances.front();
  glm::vec3 local_centre = glm::vec3(glm::inverse(inst.model) * glm::vec4(centre, 1));
  const Primitive& p = s.meshes[inst.mesh].primitives.front();
  ASSERT_EQ(p.index_count % 3, 0u);
  for (std::uint32_t i = p.first_index; i < p.first_index + p.index_count; i += 3) {
    const Vertex &a = s.vertices[s.indices[i]], &b = s.vertices[s.indices[i + 1]], &c = s.vertices[s.indices[i + 2]];
    glm::vec3 face = glm::normalize(glm::cross(b.position - a.position, c.position - a.position));
    for (const Vertex* v : {&a, &b, &c}) {
      EXPECT_NEAR(glm::length(v->normal), 1.f, 1e-4f);
      EXPECT_NEAR(glm::dot(v->normal, face), 1.f, 1e-4f) << "a flat-shaded cube keeps its face normals";
      EXPECT_GT(glm::dot(v->normal, (a.position + b.position + c.position) / 3.f - local_centre), 0.f) << "outward";
      EXPECT_NEAR(glm::dot(v->normal, glm::vec3(v->tangent)), 0.f, 1e-4f);
      EXPECT_NEAR(glm::length(glm::vec3(v->tangent)), 1.f, 1e-4f);
    }
  }
}

TEST(Scene, NoCameraLoadsButHasNoViews) {
  Scene s = load_scene(from_root("tests/data/no_camera.gltf"));
  EXPECT_TRUE(s.cameras.empty());
}

TEST(Scene, TangentsFromUvsFollowTheGltfConvention) {
  // A quad facing +z, textured the usual glTF way: u to the right (+x), v down the image
  // (-y). The tangent follows +u and the bitangent cross(N, T) * w must point up (+y).
  std::vector<Vertex> v(4);
  v[0].position = {0, 0, 0}; v[0].uv = {0, 1};
  v[1].position = {1, 0, 0}; v[1].uv = {1, 1};
  v[2].position = {1, 1, 0}; v[2].uv = {1, 0};
  v[3].position = {0, 1, 0}; v[3].uv = {0, 0};
  for (auto& x : v) x.normal = {0, 0, 1};
  std::vector<std::uint32_t> idx = {0, 1, 2, 0, 2, 3};
  generate_tangents(v, idx, 0, 6, true);
  for (const auto& x : v) {
    EXPECT_NEAR(x.tangent.x, 1.f, 1e-5f);
    glm::vec3 bitangent = glm::cross(x.normal, glm::vec3(x.tangent)) * x.tangent.w;
    EXPECT_NEAR(bitangent.y, 1.f, 1e-5f) << "the normal map's green channel must point up the image";
  }
  // Mirrored UVs (v running up) flip the handedness.
  for (auto& x : v) x.uv.y = 1.f - x.uv.y;
  generate_tangents(v, idx, 0, 6, true);
  for (const auto& x : v) EXPECT_FLOAT_EQ(x.tangent.w, -1.f);
}
