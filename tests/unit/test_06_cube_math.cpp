// Chapter 06's cube maps (cube_math.h) without OpenGL: the face and (s, t) a lookup reads,
// against the face's view and projection the depth pass draws with.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "chapters/06_shadows/cube_math.h"

using namespace lp::ch06;

namespace {
// Where the depth pass draws a point `d` away from the light on `face`: clip-space x, y over w
// as a texel position (s, t), and whether it lies inside the face's frustum.
struct Drawn {
  glm::vec2 st;
  bool inside;
};
Drawn drawn(glm::vec3 d, CubeFace face) {
  const glm::vec3 light(0.3f, -1.2f, 2.f);
  const glm::vec4 clip = cube_face_view_projection(light, face, 50.f) * glm::vec4(light + d, 1.f);
  const glm::vec3 ndc = glm::vec3(clip) / clip.w;
  return {0.5f * (glm::vec2(ndc) + 1.f), clip.w > 0.f && std::abs(ndc.x) <= 1.f && std::abs(ndc.y) <= 1.f};
}
}  // namespace

// The axes read their own faces' centres; OpenGL's table for a few directions by hand.
TEST(CubeMath, EachAxisReadsTheCentreOfItsFace) {
  const glm::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int f = 0; f < 6; ++f) {
    const CubeCoords c = cube_face_coords(axes[f] * 3.f);
    EXPECT_EQ(int(c.face), f);
    EXPECT_NEAR(c.st.x, 0.5f, 1e-6f);
    EXPECT_NEAR(c.st.y, 0.5f, 1e-6f);
  }
  // +X: sc = -z, tc = -y over |x|; -Y: sc = x, tc = -z over |y|.
  const CubeCoords px = cube_face_coords({2.f, 1.f, 0.5f});
  EXPECT_EQ(px.face, CubeFace::PositiveX);
  EXPECT_NEAR(px.st.x, 0.5f * (-0.25f + 1.f), 1e-6f);
  EXPECT_NEAR(px.st.y, 0.5f * (-0.5f + 1.f), 1e-6f);
  const CubeCoords ny = cube_face_coords({0.5f, -2.f, 1.f});
  EXPECT_EQ(ny.face, CubeFace::NegativeY);
  EXPECT_NEAR(ny.st.x, 0.5f * (0.25f + 1.f), 1e-6f);
  EXPECT_NEAR(ny.st.y, 0.5f * (-0.5f + 1.f), 1e-6f);
}

// Every direction is drawn on the face the lookup reads, at the (s, t) it reads there, and on no
// other face's frustum beyond a rounding's width of its edge: the six faces tile the sphere.
TEST(CubeMath, TheDepthPassDrawsEachDirectionWhereTheLookupReadsIt) {
  std::mt19937 rng(25);
  std::normal_distribution<float> normal;
  int checked = 0;
  for (int i = 0; i < 20000; ++i) {
    const glm::vec3 d = glm::vec3(normal(rng), normal(rng), normal(rng)) * 4.f;
    if (glm::length(d) < 0.2f) continue;
    const CubeCoords c = cube_face_coords(d);
    const Drawn on = drawn(d, c.face);
    ASSERT_TRUE(on.inside) << i;
    // The projection's rounding: a few ulps of ndc.
    EXPECT_NEAR(on.st.x, c.st.x, 1e-5f) << "face " << int(c.face) << ", direction " << i;
    EXPECT_NEAR(on.st.y, c.st.y, 1e-5f) << "face " << int(c.face) << ", direction " << i;
    for (int f = 0; f < 6; ++f) {
      if (f == int(c.face)) continue;
      const Drawn other = drawn(d, CubeFace(f));
      // Another face may hold it only on its very edge (a direction on a seam belongs to both).
      if (other.inside) {
        EXPECT_TRUE(std::min({other.st.x, other.st.y, 1.f - other.st.x, 1.f - other.st.y}) < 1e-4f) << i << " on " << f;
      }
    }
    ++checked;
  }
  EXPECT_GT(checked, 19000);
}

// A seam: two directions a hair apart on either side of the +X / -Z boundary read neighbouring
// faces, each at its edge, and the same point of the cube: the map is continuous across it.
TEST(CubeMath, DirectionsAcrossASeamMeetAtTheFacesEdges) {
  for (float y : {-0.8f, -0.3f, 0.f, 0.45f, 0.9f}) {
    const CubeCoords a = cube_face_coords({1.f + 1e-4f, y, -1.f});
    const CubeCoords b = cube_face_coords({1.f - 1e-4f, y, -1.f});
    EXPECT_EQ(a.face, CubeFace::PositiveX);
    EXPECT_EQ(b.face, CubeFace::NegativeZ);
    // +X's s = (-z / |x| + 1) / 2 reaches 1 at z = -x; -Z's s = (-x / |z| + 1) / 2 reaches 0 at x = -z.
    EXPECT_NEAR(a.st.x, 1.f, 1e-3f);
    EXPECT_NEAR(b.st.x, 0.f, 1e-3f);
    // Both faces' t along the shared edge: -y over the major axis, the same height.
    EXPECT_NEAR(a.st.y, b.st.y, 1e-3f);
    // And the depth pass draws each at that edge of its own face.
    EXPECT_NEAR(drawn({1.f + 1e-4f, y, -1.f}, CubeFace::PositiveX).st.x, 1.f, 1e-3f);
    EXPECT_NEAR(drawn({1.f - 1e-4f, y, -1.f}, CubeFace::NegativeZ).st.x, 0.f, 1e-3f);
  }
}

TEST(CubeMath, TheFarPlaneReachesTheScenesFarthestCornerOrTheRange) {
  EXPECT_NEAR(cube_far({0, 0, 0}, 0.f, {-1, -2, -3}, {1, 2, 3}), std::sqrt(14.f), 1e-5f);
  EXPECT_NEAR(cube_far({0, 0, 0}, 2.f, {-1, -2, -3}, {1, 2, 3}), 2.f, 1e-6f);
  EXPECT_NEAR(cube_far({0, 0, 0}, 0.f, {0, 0, 0}, {0, 0, 0}), 2.f * kCubeNear, 1e-7f);  // never below the near plane
  EXPECT_NEAR(cube_texel_world(3.f, 512), 6.f / 512.f, 1e-7f);
}
