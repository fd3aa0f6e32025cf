// glTF loading: our scenes load cleanly; bad files give errors that say what and where;
// missing data is generated or replaced with a warning.
#include <gtest/gtest.h>

#include <algorithm>

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <iterator>
#include <fstream>

#include <nlohmann/json.hpp>

#include "common/error.h"
#include "common/paths.h"
#include "common/scene.h"

using namespace lp;

namespace {
std::string load_error(const std::filesystem::path& file) {
  try {
    load_scene(file.is_absolute() ? file : from_root("tests/data" / file));
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

Scene data(const std::string& file) { return load_scene(from_root("tests/data/" + file)); }

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::string all_warnings(const Scene& s) {
  std::string w;
  for (const auto& x : s.warnings) w += x + "\n";
  return w;
}

glm::vec3 face_normal(const Scene& s, std::uint32_t first) {
  const Vertex &a = s.vertices[s.indices[first]], &b = s.vertices[s.indices[first + 1]], &c = s.vertices[s.indices[first + 2]];
  return glm::normalize(glm::cross(b.position - a.position, c.position - a.position));
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

TEST(Scene, AlphaModeBlendIsKeptAndSaidOnce) {
  // Chapter 10's glass: alphaMode BLEND becomes Material::blend (no warning), with the base
  // colour's alpha; the opaque materials stay opaque; a note says what the chapters do with it.
  Scene s = load_scene(from_root("assets/glass/glass.gltf"));
  EXPECT_TRUE(s.warnings.empty()) << (s.warnings.empty() ? "" : s.warnings.front());
  int blended = 0;
  for (const Material& m : s.materials) {
    EXPECT_EQ(m.blend, m.name.rfind("glass_", 0) == 0) << m.name;
    if (m.blend) {
      ++blended;
      EXPECT_LT(m.base_color.a, 1.f) << m.name;
    }
  }
  EXPECT_EQ(blended, 7);
  EXPECT_EQ(std::count_if(s.notes.begin(), s.notes.end(), [](const std::string& n) { return n.find("alphaMode BLEND") != std::string::npos; }), 1);
  for (const char* name : {"forward", "atrium", "street", "cornell"})
    for (const Material& m : load_scene(from_root(std::string("assets/") + name + "/" + name + ".gltf")).materials)
      EXPECT_FALSE(m.blend) << name << ": " << m.name;
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

TEST(Scene, NoCameraGetsTheAutomaticViewAndSaysSo) {
  Scene s = load_scene(from_root("tests/data/no_camera.gltf"));
  ASSERT_EQ(s.cameras.size(), 1u);
  EXPECT_EQ(s.cameras.front().name, kAutoView);
  ASSERT_EQ(s.notes.size(), 1u);
  EXPECT_NE(s.notes.front().find("has no camera: rendering view 'auto'"), std::string::npos) << s.notes.front();
  EXPECT_EQ(s.lights.size(), 1u) << "the file's own light: no default rig";
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

// ---- Real models -------------------------------------------------------------------------

TEST(Scene, MissingNormalsAreFlatEvenWhereCornersAreShared) {
  // 8 shared corners: smooth (averaged) normals would point along the diagonals.
  Scene s = data("indexed_nonormals.gltf");
  ASSERT_EQ(s.indices.size(), 36u);
  for (std::uint32_t t = 0; t < 36; t += 3) {
    glm::vec3 face = face_normal(s, t);
    for (int k = 0; k < 3; ++k) {
      const Vertex& v = s.vertices[s.indices[t + k]];
      EXPECT_NEAR(glm::dot(v.normal, face), 1.f, 1e-5f) << "triangle " << t / 3;
      EXPECT_NEAR(glm::dot(v.normal, glm::vec3(v.tangent)), 0.f, 1e-5f);
    }
    EXPECT_NEAR(std::max({std::abs(face.x), std::abs(face.y), std::abs(face.z)}), 1.f, 1e-5f) << "an axis, not a diagonal";
  }
}

TEST(Scene, StripsAndFansBecomeTrianglesWithTheirWinding) {
  Scene s = data("strip_fan.gltf");
  ASSERT_EQ(s.meshes.size(), 2u);
  EXPECT_EQ(s.meshes[0].primitives.at(0).index_count, 2u * 3) << "a 4-vertex strip is 2 triangles";
  EXPECT_EQ(s.meshes[1].primitives.at(0).index_count, 4u * 3) << "a 6-vertex fan is 4 triangles";
  for (const auto& m : s.meshes)
    for (std::uint32_t t = m.primitives[0].first_index; t < m.primitives[0].first_index + m.primitives[0].index_count; t += 3)
      EXPECT_NEAR(face_normal(s, t).y, 1.f, 1e-5f) << m.name << ": every triangle keeps the counter-clockwise winding (+Y)";
  EXPECT_TRUE(s.warnings.empty()) << all_warnings(s);
}

TEST(Scene, PointsAndLinesAreSkippedWithOneWarning) {
  Scene s = data("lines_and_triangles.gltf");
  ASSERT_EQ(s.warnings.size(), 1u) << all_warnings(s);
  EXPECT_TRUE(contains(s.warnings[0], "lines (skipped)")) << s.warnings[0];
  EXPECT_EQ(s.meshes.at(0).primitives.size(), 1u);
  EXPECT_TRUE(contains(load_error("points_only.gltf"), "no triangles to draw (1 primitives are points or lines"))
      << load_error("points_only.gltf");
}

TEST(Scene, ARequiredExtensionWeLackIsRefusedByName) {
  EXPECT_TRUE(contains(load_error("requires_draco.gltf"), "requires the extension KHR_draco_mesh_compression"))
      << load_error("requires_draco.gltf");
  EXPECT_TRUE(contains(load_error("requires_meshopt.gltf"), "requires the extension EXT_meshopt_compression"))
      << load_error("requires_meshopt.gltf");
}

TEST(Scene, AnExtensionOnlyUsedLoadsWithOneWarningNamingIt) {
  Scene s = data("uses_clearcoat.gltf");
  ASSERT_EQ(s.warnings.size(), 1u) << all_warnings(s);
  EXPECT_TRUE(contains(s.warnings[0], "extension KHR_materials_clearcoat")) << s.warnings[0];
  EXPECT_FALSE(contains(s.warnings[0], "(x")) << "named once, though the file names it twice: " << s.warnings[0];
}

TEST(Scene, BinaryGltfIsToldByItsContentNotItsName) {
  Scene glb = data("glb_content.gltf"), text = data("minimal.gltf");
  ASSERT_EQ(glb.vertices.size(), text.vertices.size());
  for (size_t i = 0; i < glb.vertices.size(); ++i) EXPECT_EQ(glb.vertices[i].position, text.vertices[i].position);
  EXPECT_EQ(glb.cameras.front().name, "view");
}

TEST(Scene, TextureTransformIsAppliedToTheUvs) {
  Scene t = data("texture_transform.gltf"), plain = data("minimal.gltf");
  ASSERT_EQ(t.vertices.size(), plain.vertices.size());
  // KHR_texture_transform: uv' = T(0.5, 0.25) R(pi/2) S(2, 3) uv, R = [cos sin; -sin cos].
  for (size_t i = 0; i < t.vertices.size(); ++i) {
    glm::vec2 uv = plain.vertices[i].uv * glm::vec2(2, 3);
    glm::vec2 expected = glm::vec2(uv.y, -uv.x) + glm::vec2(0.5f, 0.25f);
    EXPECT_NEAR(t.vertices[i].uv.x, expected.x, 1e-5f) << i;
    EXPECT_NEAR(t.vertices[i].uv.y, expected.y, 1e-5f) << i;
  }
  EXPECT_TRUE(t.warnings.empty()) << "a required KHR_texture_transform is supported: " << all_warnings(t);
}

TEST(Scene, EmissiveTextureAndStrengthAreRead) {
  Scene s = data("emissive_texture.gltf");
  const Material& m = s.materials.at(0);
  EXPECT_EQ(m.emissive, glm::vec3(2.f, 1.f, 0.5f)) << "emissiveFactor x KHR_materials_emissive_strength 2";
  ASSERT_GE(m.emissive_texture, 0);
  EXPECT_TRUE(s.textures[m.emissive_texture].srgb);
  EXPECT_FALSE(s.textures[m.emissive_texture].fallback);
  EXPECT_TRUE(s.warnings.empty()) << all_warnings(s);
}

TEST(Scene, DoubleSidedIsReadAndNotWarnedAbout) {
  // minimal.gltf with its material made doubleSided, written beside its buffer in a temp
  // folder: the flag reaches the material (SceneGpu::draw then draws it without culling, and
  // the ray tracer's primary hits keep its back faces), and the loader no longer warns.
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("lightpass_double_sided_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  nlohmann::json doc = nlohmann::json::parse(std::ifstream(from_root("tests/data/minimal.gltf")));
  doc["materials"][0]["doubleSided"] = true;
  std::ofstream(dir / "minimal.gltf") << doc.dump();
  std::filesystem::copy_file(from_root("tests/data/minimal.bin"), dir / "minimal.bin",
                             std::filesystem::copy_options::overwrite_existing);
  Scene s = load_scene(dir / "minimal.gltf");
  std::filesystem::remove_all(dir);
  EXPECT_TRUE(s.materials.at(0).double_sided);
  EXPECT_FALSE(data("minimal.gltf").materials.at(0).double_sided);
  EXPECT_FALSE(contains(all_warnings(s), "doubleSided")) << all_warnings(s);
}

TEST(Scene, SpecularExtensionIsRead) {
  Scene s = data("minimal.gltf");  // scenegen writes KHR_materials_specular on every material
  EXPECT_TRUE(s.materials.at(0).has_specular_extension);
}

// The automatic view: the scene's bounding sphere inside the vertical field of view, and
// filling most of it (the distance puts the sphere 5 % inside the frustum's top and bottom).
TEST(Scene, AutoViewFramesTheBoundsAndTheDefaultRigLightsThem) {
  Scene s = data("no_camera_no_lights.gltf");
  ASSERT_EQ(s.cameras.size(), 1u);
  const Camera& c = s.cameras[0];
  EXPECT_EQ(c.name, kAutoView);
  glm::vec3 centre = 0.5f * (s.bounds_min + s.bounds_max);
  float radius = 0.5f * glm::length(s.bounds_max - s.bounds_min);
  glm::vec3 to_centre = glm::vec3(c.view() * glm::vec4(centre, 1));
  EXPECT_NEAR(to_centre.x, 0.f, 1e-4f);
  EXPECT_NEAR(to_centre.y, 0.f, 1e-4f);
  float distance = -to_centre.z;
  float half_angle = std::asin(radius / distance);  // the sphere's angular radius
  EXPECT_LT(half_angle, 0.5f * c.yfov);
  EXPECT_GT(half_angle, 0.4f * c.yfov);
  EXPECT_LT(c.znear, distance - radius);
  EXPECT_GT(c.zfar, distance + radius);
  ASSERT_EQ(s.lights.size(), 2u);
  for (const Light& l : s.lights) {
    EXPECT_EQ(l.type, LightType::Directional);
    EXPECT_LT(glm::dot(l.direction, glm::vec3(c.world[2])), 0.f) << l.name << " shines away from the viewer, onto the visible side";
  }
  // The key (the brighter light) comes from the side and from above the view, so the
  // shadows it casts fall sideways, where the view sees them, not behind the model.
  const glm::vec3 right(c.world[0]), up(c.world[1]), back(c.world[2]);
  const Light& key = s.lights[0].intensity >= s.lights[1].intensity ? s.lights[0] : s.lights[1];
  EXPECT_GT(std::abs(glm::dot(-key.direction, right)), 0.5f) << "the key light is not from the side";
  EXPECT_GT(glm::dot(-key.direction, up), 0.5f) << "the key light is not from above";
  // Exposure: on a surface facing up, or facing the view, the rig gives at most 1 (an albedo
  // of 1 does not clip), and at least 0.5 (a grey floor is not dim).
  for (const glm::vec3 n : {glm::vec3(0, 1, 0), back}) {
    float e = s.ambient.x;
    for (const Light& l : s.lights) e += l.intensity * std::max(0.f, glm::dot(n, -l.direction));
    EXPECT_LE(e, 1.f) << "normal " << n.x << " " << n.y << " " << n.z;
    EXPECT_GE(e, 0.5f) << "normal " << n.x << " " << n.y << " " << n.z;
  }
  ASSERT_EQ(s.notes.size(), 2u);
  EXPECT_TRUE(contains(s.notes[1], "has no lights: using a default rig")) << s.notes[1];
}

TEST(Scene, AutoViewComesAfterTheNamedCameras) {
  Scene s = data("minimal.gltf");
  ASSERT_EQ(s.cameras.size(), 2u);
  EXPECT_EQ(s.cameras[0].name, "view");
  EXPECT_EQ(s.cameras[1].name, kAutoView);
  EXPECT_TRUE(s.notes.empty()) << "the file's camera is the default view: nothing to say";
}

// ---- Bad values: an error naming the camera, a warning naming the light -----------------

TEST(Scene, DegenerateCamerasAreErrorsNamingTheCamera) {
  const std::pair<const char*, const char*> cases[] = {
      {"camera_yfov_zero.gltf", "camera 'view': yfov 0 is not between 0 and pi"},
      {"camera_yfov_pi.gltf", "camera 'view': yfov 3.14159 is not between 0 and pi"},
      {"camera_znear_zero.gltf", "camera 'view': znear 0 must be > 0"},
      {"camera_zfar_below_znear.gltf", "camera 'view': zfar 0.01 must be greater than znear 0.05"},
      {"camera_zero_scale.gltf", "camera 'view': its node's transform has a zero (or non-finite) scale"},
      {"camera_zero_quaternion.gltf", "node 'view': its rotation is not a unit quaternion (length 0)"},
  };
  for (const auto& [file, message] : cases) EXPECT_TRUE(contains(load_error(file), message)) << file << ": " << load_error(file);
}

TEST(Scene, InvalidLightsAreLeftOutNamingEach) {
  Scene s = data("lights_invalid.gltf");
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].name, "light");
  std::string w = all_warnings(s);
  for (const char* part : {"light 'negative_intensity' is left out: its intensity -5", "light 'negative_colour' is left out: its colour",
                           "light 'infinite_intensity' is left out: its intensity inf", "light 'negative_range' is left out: its range -3"})
    EXPECT_TRUE(contains(w, part)) << part << " in\n" << w;
}

// ---- Hostile files: refused with a message, in bounded time ------------------------------

TEST(Scene, AccessorBoundsArithmeticCannotWrap) {
  EXPECT_TRUE(contains(load_error("accessor_offset_overflow.gltf"), "accessor 0 (4 elements of 12 bytes, stride 12, offset 18446744073709551600) reads past the end"))
      << load_error("accessor_offset_overflow.gltf");
  EXPECT_TRUE(contains(load_error("accessor_count_overflow.gltf"), "accessor 0 (4611686018427387904 elements")) << load_error("accessor_count_overflow.gltf");
  EXPECT_TRUE(contains(load_error("huge_index_count.gltf"), "indices: accessor 4 (4000000000 elements")) << load_error("huge_index_count.gltf");
}

TEST(Scene, SharedChildrenCannotExpandWithoutBound) {
  auto start = std::chrono::steady_clock::now();
  EXPECT_TRUE(contains(load_error("node_dag.gltf"), "more than 1000000 mesh instances")) << load_error("node_dag.gltf");
  EXPECT_TRUE(contains(load_error("node_dag_no_mesh.gltf"), "expands to more than 4000000 nodes")) << load_error("node_dag_no_mesh.gltf");
  EXPECT_TRUE(contains(load_error("node_dag_light.gltf"), "more than 100000 lights")) << load_error("node_dag_light.gltf");
  // 2^40 instances unbounded; bounded, a few million visits. 60 s is far above that even under
  // AddressSanitizer, and far below what the unbounded walk takes.
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 60.0);
}

TEST(Scene, JsonNestedTooDeepIsRefusedBeforeParsing) {
  auto path = std::filesystem::temp_directory_path() / "lightpass_deep.gltf";
  std::ofstream(path) << R"({"asset": {"version": "2.0"}, "extras": )" << std::string(200000, '[') << std::string(200000, ']') << "}";
  EXPECT_TRUE(contains(load_error(path), "its JSON nests deeper than 256 levels")) << load_error(path);
  std::filesystem::remove(path);
}

TEST(Scene, SixteenBitPngIsReadAsEightBits) {
  Scene s = data("texture_16bit.gltf");
  ASSERT_EQ(s.textures.size(), 1u);
  const Texture& t = s.textures[0];
  ASSERT_FALSE(t.fallback) << all_warnings(s);
  ASSERT_EQ(t.image.width, 4);
  // The file: channel c of texel (x, y) is 0xFFFF when x + y + c is odd, else 0x2000.
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x)
      for (int c = 0; c < 3; ++c) EXPECT_EQ(int(t.image.at(x, y)[c]), ((x + y + c) & 1) ? 255 : 0x20) << x << "," << y << "," << c;
  EXPECT_TRUE(contains(all_warnings(s), "16-bit images read as 8 bits per channel: 'rgb16.png'")) << all_warnings(s);
}

TEST(Scene, ImagesPastTheLoaderLimitFallBackNamingTheImage) {
  Scene s = data("texture_40000x1.gltf");
  ASSERT_EQ(s.textures.size(), 1u);
  EXPECT_TRUE(s.textures[0].fallback);
  EXPECT_TRUE(contains(all_warnings(s), "texture 'wide_40000x1.png' could not be loaded (it is 40000x1, more than the loader accepts"))
      << all_warnings(s);
  Scene wide = data("texture_20000x1.gltf");  // within the loader's limit; GL's is checked on upload
  EXPECT_FALSE(wide.textures.at(0).fallback);
  EXPECT_EQ(wide.textures.at(0).image.width, 20000);
}

TEST(Scene, UnreadableUrisSayCannotRead) {
  Scene s = data("texture_uri_directory.gltf");
  EXPECT_TRUE(s.textures.at(0).fallback);
  EXPECT_TRUE(contains(all_warnings(s), "cannot read 'tests/data/.': it is a directory") ||
              contains(all_warnings(s), "/tests/data/.': it is a directory")) << all_warnings(s);
  EXPECT_TRUE(contains(load_error("buffer_uri_directory.gltf"), "it is a directory")) << load_error("buffer_uri_directory.gltf");
  EXPECT_TRUE(contains(load_error("buffer_dev_null.gltf"), "dev/null': not a regular file")) << load_error("buffer_dev_null.gltf");
}

TEST(Scene, ASceneThatIsNotAFileSaysCannotRead) {
  EXPECT_TRUE(contains(load_error(from_root("tests/data")), "cannot read scene '")) << load_error(from_root("tests/data"));
  EXPECT_TRUE(contains(load_error(from_root("tests/data")), "': it is a directory"));
  EXPECT_TRUE(contains(load_error("/dev/null"), "cannot read scene '/dev/null': not a regular file")) << load_error("/dev/null");
}

TEST(Scene, AFileThisUserMayNotReadSaysPermissionDenied) {
  if (geteuid() == 0) GTEST_SKIP() << "root reads any file: permissions cannot be tested as root";
  auto path = std::filesystem::temp_directory_path() / "lightpass_unreadable.gltf";
  std::ofstream(path) << "{}";
  std::filesystem::permissions(path, std::filesystem::perms::none);
  EXPECT_TRUE(contains(load_error(path), "cannot read scene '" + path.string() + "': permission denied")) << load_error(path);
  std::filesystem::remove(path);
}

TEST(Scene, LightsThatGiveNoLightWarnThatTheImageWillBeBlack) {
  // minimal.gltf with its one light at zero intensity and no ambient, written beside its buffer.
  nlohmann::json doc = nlohmann::json::parse(std::ifstream(from_root("tests/data/minimal.gltf")));
  doc["extensions"]["KHR_lights_punctual"]["lights"][0]["intensity"] = 0;
  doc["scenes"][0]["extras"]["lightpass"]["ambient"] = {0, 0, 0};
  auto dir = std::filesystem::temp_directory_path() / "lightpass_black";
  std::filesystem::create_directories(dir);
  std::filesystem::copy_file(from_root("tests/data/minimal.bin"), dir / "minimal.bin", std::filesystem::copy_options::overwrite_existing);
  doc["buffers"][0]["uri"] = "minimal.bin";
  std::ofstream(dir / "black.gltf") << doc.dump();
  Scene s = load_scene(dir / "black.gltf");
  EXPECT_EQ(s.lights.size(), 1u) << "a zero light is allowed, and no default rig replaces it";
  EXPECT_TRUE(contains(all_warnings(s), "the image will be black")) << all_warnings(s);
  std::filesystem::remove_all(dir);
}

TEST(Scene, VertexAndIndexLimitsAreCheckedBeforeAllocating) {
  auto error = [](const char* file, SceneLimits limits) {
    try {
      load_scene(from_root(std::string("tests/data/") + file), limits);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_TRUE(contains(error("minimal.gltf", {.max_vertices = 3}), "has 4 vertices; with the scene's 0 that is more than the loader accepts (3)"))
      << error("minimal.gltf", {.max_vertices = 3});
  // 8 corners fit in 20, but flat shading un-indexes them into 36 vertices.
  EXPECT_TRUE(contains(error("indexed_nonormals.gltf", {.max_vertices = 20}), "would hold more than 20 vertices"))
      << error("indexed_nonormals.gltf", {.max_vertices = 20});
  // A 6-vertex fan is 12 indices: past a limit of 10 before it is converted.
  EXPECT_TRUE(contains(error("strip_fan.gltf", {.max_indices = 10}), "mesh 'fan' primitive 0: the scene would hold more than"))
      << error("strip_fan.gltf", {.max_indices = 10});
}

// A light node's extras.lightpass.casts_shadows: true or false where the file says so (the
// light's casts_shadows), unset where it does not (a chapter's default applies: book/
// appendix-scenes.md), and anything but a boolean refused with the node named.
TEST(Scene, ALightNodeMarksWhetherTheLightCastsShadows) {
  auto dir = std::filesystem::temp_directory_path() / "lightpass_casts_shadows";
  std::filesystem::create_directories(dir);
  std::filesystem::copy_file(from_root("tests/data/minimal.bin"), dir / "minimal.bin", std::filesystem::copy_options::overwrite_existing);
  auto with = [&](const nlohmann::json* mark) {
    nlohmann::json doc = nlohmann::json::parse(std::ifstream(from_root("tests/data/minimal.gltf")));
    doc["buffers"][0]["uri"] = "minimal.bin";
    for (auto& node : doc["nodes"])
      if (node.contains("extensions") && mark) node["extras"]["lightpass"]["casts_shadows"] = *mark;
    std::ofstream(dir / "marked.gltf") << doc.dump();
    return dir / "marked.gltf";
  };
  EXPECT_FALSE(load_scene(with(nullptr)).lights.at(0).casts_shadows.has_value());
  const nlohmann::json yes = true, no = false, text = "yes";
  EXPECT_EQ(load_scene(with(&yes)).lights.at(0).casts_shadows, std::optional<bool>(true));
  EXPECT_EQ(load_scene(with(&no)).lights.at(0).casts_shadows, std::optional<bool>(false));
  const std::string e = load_error(with(&text));
  EXPECT_TRUE(contains(e, "node 'light': extras.lightpass.casts_shadows must be true or false")) << e;
  std::filesystem::remove_all(dir);
}

// Memory is bounded for all images together (SceneLimits::max_total_texels), and one file
// named by many images is decoded and counted once. image_shared_16.gltf names stripes.png
// (8 x 8 = 64 texels) in 16 images: with a total budget of 64 texels it loads, as one texture.
TEST(Scene, ImagesOfTheSameBytesAreCountedOnce) {
  SceneLimits limits;
  limits.max_total_texels = 64;
  Scene s = load_scene(from_root("tests/data/image_shared_16.gltf"), limits);
  EXPECT_TRUE(s.warnings.empty()) << all_warnings(s);
  ASSERT_EQ(s.textures.size(), 1u);
  EXPECT_FALSE(s.textures[0].fallback);
  EXPECT_EQ(s.textures[0].image.width, 8);
}

// Two distinct images (stripes.png, 64 texels, then rgb16.png, 16) under a total of 70: the
// first loads, the second gets the fallback checker with a warning that names the budget.
TEST(Scene, TheTotalTexelBudgetIsNamed) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("lightpass_texel_budget_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  nlohmann::json doc = nlohmann::json::parse(std::ifstream(from_root("tests/data/minimal.gltf")));
  doc["images"] = {{{"uri", "stripes.png"}}, {{"uri", "rgb16.png"}}};
  doc["textures"] = {{{"source", 0}}, {{"source", 1}}};
  doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
  doc["materials"][0]["emissiveTexture"] = {{"index", 1}};
  std::ofstream(dir / "minimal.gltf") << doc.dump();
  for (const char* f : {"minimal.bin", "stripes.png", "rgb16.png"})
    std::filesystem::copy_file(from_root(std::string("tests/data/") + f), dir / f, std::filesystem::copy_options::overwrite_existing);
  SceneLimits limits;
  limits.max_total_texels = 70;
  Scene tight = load_scene(dir / "minimal.gltf", limits);
  limits.max_total_texels = 80;
  Scene enough = load_scene(dir / "minimal.gltf", limits);
  std::filesystem::remove_all(dir);
  const Material& m = tight.materials.at(0);
  EXPECT_FALSE(tight.textures.at(m.base_color_texture).fallback);
  EXPECT_TRUE(tight.textures.at(m.emissive_texture).fallback);
  EXPECT_TRUE(contains(all_warnings(tight), "texture 'rgb16.png' could not be loaded (it is 4x4, and with the scene's other images "
                                            "(64 texels) that is more than the loader accepts in all (70 texels"))
      << all_warnings(tight);
  EXPECT_FALSE(enough.textures.at(enough.materials.at(0).emissive_texture).fallback) << all_warnings(enough);
}

// An index accessor without a bufferView (zeros: glTF allows it, tinygltf refuses it) is taken
// out of the JSON before tinygltf reads it; in a .glb the file is rebuilt around the new JSON.
// indices_no_buffer_view.gltf as a .glb (its buffer the BIN chunk) loads like the .gltf: the
// plane's primitive drawn, the zero one counted as no area and left out.
TEST(Scene, IndicesWithoutABufferViewLoadFromAGlbToo) {
  nlohmann::json doc = nlohmann::json::parse(std::ifstream(from_root("tests/data/indices_no_buffer_view.gltf")));
  doc["buffers"][0].erase("uri");
  std::ifstream bin_file(from_root("tests/data/minimal.bin"), std::ios::binary);
  std::vector<unsigned char> bin((std::istreambuf_iterator<char>(bin_file)), std::istreambuf_iterator<char>());
  std::string text = doc.dump();
  while (text.size() % 4) text += ' ';
  while (bin.size() % 4) bin.push_back(0);
  std::vector<unsigned char> glb = {'g', 'l', 'T', 'F'};
  auto u32 = [&](std::uint32_t v) { for (int i = 0; i < 4; ++i) glb.push_back(static_cast<unsigned char>(v >> (8 * i))); };
  u32(2);
  u32(static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + bin.size()));
  u32(static_cast<std::uint32_t>(text.size()));
  u32(0x4E4F534Au);
  glb.insert(glb.end(), text.begin(), text.end());
  u32(static_cast<std::uint32_t>(bin.size()));
  u32(0x004E4942u);
  glb.insert(glb.end(), bin.begin(), bin.end());
  Scene s = load_scene_from_memory(glb, from_root("tests/data/indices_no_buffer_view.glb"));
  Scene gltf = data("indices_no_buffer_view.gltf");
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].primitives.size(), 1u);
  EXPECT_EQ(s.indices, gltf.indices);
  EXPECT_EQ(s.meshes[0].primitives.size(), gltf.meshes[0].primitives.size());
}
