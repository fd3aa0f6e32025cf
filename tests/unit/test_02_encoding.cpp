// Chapter 02's maths on the CPU (encoding.h, depth.h): every normal encoding's round trip
// over the whole sphere within its stated bound, the exponent code, and the position
// reconstructed from each depth format at near and far distances.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "chapters/02_gbuffer/depth.h"
#include "chapters/02_gbuffer/encoding.h"
#include "chapters/02_gbuffer/layout.h"

using namespace lp;
using namespace lp::ch02;

namespace {

double angle(const glm::vec3& a, const glm::vec3& b) {
  glm::dvec3 x(a), y(b);
  return std::atan2(glm::length(glm::cross(x, y)), glm::dot(x, y));
}

// A Fibonacci spiral over the sphere, plus the places encodings get wrong: both poles, the
// equator (the octahedron's fold, where z changes sign), just either side of it, the folded
// corners (the lower pole maps to all four corners of the square) and the diagonals.
std::vector<glm::vec3> hard_directions() {
  std::vector<glm::vec3> d;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    double z = 1.0 - 2.0 * (i + 0.5) / n, r = std::sqrt(1.0 - z * z), a = 2.399963229728653 * i;
    d.emplace_back(float(r * std::cos(a)), float(r * std::sin(a)), float(z));
  }
  for (int i = 0; i < 720; ++i) {
    double a = i * 6.283185307179586 / 720;
    glm::vec3 e(float(std::cos(a)), float(std::sin(a)), 0.f);
    d.push_back(e);
    for (float z : {-1e-6f, 1e-6f, -1e-3f, 1e-3f}) d.push_back(glm::normalize(e + glm::vec3(0, 0, z)));
    for (float r : {1e-6f, 1e-3f}) {  // around both poles
      d.push_back(glm::normalize(glm::vec3(e.x * r, e.y * r, 1.f)));
      d.push_back(glm::normalize(glm::vec3(e.x * r, e.y * r, -1.f)));
    }
  }
  for (float x : {-1.f, 0.f, 1.f})
    for (float y : {-1.f, 0.f, 1.f})
      for (float z : {-1.f, 0.f, 1.f})
        if (x || y || z) d.push_back(glm::normalize(glm::vec3(x, y, z)));
  return d;
}

const std::vector<glm::vec3>& directions() {
  static const std::vector<glm::vec3> d = hard_directions();
  return d;
}

}  // namespace

TEST(SignedCodes, ZeroAndBothEndsAreExact) {
  for (int bits : {8, 10, 16}) {
    EXPECT_EQ(signed_value(signed_code(0.f, bits), bits), 0.f) << bits;
    EXPECT_EQ(signed_value(signed_code(1.f, bits), bits), 1.f) << bits;
    EXPECT_EQ(signed_value(signed_code(-1.f, bits), bits), -1.f) << bits;
    EXPECT_EQ(signed_code(1.f, bits), (1u << bits) - 2u) << "the top code is left unused";
  }
}

TEST(Octahedral, FoldAndUnfoldAreInverseWithoutQuantisation) {
  double worst = 0;
  for (const auto& n : directions()) worst = std::max(worst, angle(n, octahedral_unfold(octahedral_fold(n))));
  EXPECT_LT(worst, 1e-6);  // float rounding only
  for (const auto& n : directions()) {
    glm::vec2 p = octahedral_fold(n);
    ASSERT_LE(std::max(std::abs(p.x), std::abs(p.y)), 1.f) << "the whole sphere maps into [-1, 1]^2";
    if (n.z > 0) {
      ASSERT_LE(std::abs(p.x) + std::abs(p.y), 1.f + 1e-6f) << "the upper half inside the diamond";
    } else if (n.z < 0) {
      ASSERT_GE(std::abs(p.x) + std::abs(p.y), 1.f - 1e-6f) << "the lower half folded over its corners";
    }
  }
}

TEST(Octahedral, PolesSurviveEveryBitDepthExactly) {
  // Zero and +-1 are exact codes, so +z (the square's centre) and -z (its corners) come back
  // without error, whatever the number of bits.
  for (int bits : {8, 10, 16}) {
    EXPECT_LT(angle(glm::vec3(0, 0, 1), decode_octahedral(encode_octahedral({0, 0, 1}, bits), bits)), 1e-6) << bits;
    EXPECT_LT(angle(glm::vec3(0, 0, -1), decode_octahedral(encode_octahedral({0, 0, -1}, bits), bits)), 1e-6) << bits;
    for (auto axis : {glm::vec3(1, 0, 0), glm::vec3(-1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, -1, 0)})
      EXPECT_LT(angle(axis, decode_octahedral(encode_octahedral(axis, bits), bits)), 1e-6) << bits;
  }
}

TEST(Octahedral, RoundTripWithinItsBoundOverTheSphere) {
  // Stated bound: 3 s / sqrt(2) with s = 1 / (2^(bits-1) - 1) (encoding.h). It is tight:
  // nearest rounding reaches 99 % of it, so the bound is not a loose guess.
  for (int bits : {8, 10, 16}) {
    double bound = octahedral_error_bound(bits);
    for (bool best : {false, true}) {
      double worst = 0, sum = 0;
      for (const auto& n : directions()) {
        double a = angle(n, decode_octahedral(encode_octahedral(n, bits, best), bits));
        worst = std::max(worst, a);
        sum += a;
      }
      EXPECT_LE(worst, bound) << bits << " bits, " << (best ? "best of four" : "nearest");
      if (best) {
        EXPECT_LT(worst, 0.75 * bound) << "best-of-four rounding should cut the worst error by a quarter or more";
      } else {
        EXPECT_GT(worst, 0.9 * bound) << "the bound should be close to the real worst case";
      }
      EXPECT_LT(sum / directions().size(), 0.4 * bound);
    }
  }
}

TEST(Octahedral, NoJumpAcrossTheFold) {
  // Directions either side of the equator must decode to neighbours, not to mirrored points.
  for (int bits : {8, 16}) {
    for (int i = 0; i < 360; ++i) {
      double a = i * 0.017453292519943295;
      glm::vec3 above = glm::normalize(glm::vec3(std::cos(a), std::sin(a), 1e-4f));
      glm::vec3 below = glm::normalize(glm::vec3(std::cos(a), std::sin(a), -1e-4f));
      glm::vec3 da = decode_octahedral(encode_octahedral(above, bits), bits);
      glm::vec3 db = decode_octahedral(encode_octahedral(below, bits), bits);
      EXPECT_LT(angle(da, db), 2 * octahedral_error_bound(bits) + 2e-4) << "azimuth " << i << " deg, " << bits << " bits";
    }
  }
}

TEST(Xyz, SourceEncodingWithinItsBoundAndNeverZero) {
  double bound = xyz_error_bound(10), worst = 0;
  for (const auto& n : directions()) {
    glm::vec3 d = decode_xyz(encode_xyz(n, 10), 10);
    ASSERT_TRUE(std::isfinite(d.x) && std::isfinite(d.y) && std::isfinite(d.z));
    worst = std::max(worst, angle(n, d));
  }
  EXPECT_LE(worst, bound);
  EXPECT_GT(worst, 0.8 * bound);
  // 0 sits between two codes (511.5 of 1023): an axis comes back slightly tilted.
  EXPECT_GT(angle(glm::vec3(0, 0, 1), decode_xyz(encode_xyz({0, 0, 1}, 10), 10)), 1e-4);
}

TEST(Normals, SixteenBitOctahedralBeatsTheSourcesThirtyBits) {
  // The measurement that chose our normal: 32 bits in both targets, 40x smaller error.
  EXPECT_LT(octahedral_error_bound(16) * 25, xyz_error_bound(10));
  EXPECT_GT(octahedral_error_bound(10), xyz_error_bound(10)) << "10+10 octahedral is worse than the source's 30 bits";
}

TEST(Exponent, LogCodeKeepsRelativeErrorBelowItsBound) {
  double bound = exponent_relative_error_bound();
  EXPECT_NEAR(bound, 0.0178, 1e-3);
  double worst = 0;
  std::uint32_t previous = 0;
  for (float n = 1.f; n <= 8192.f; n *= 1.001f) {
    std::uint32_t code = encode_exponent(n);
    EXPECT_GE(code, previous) << "monotonic";
    previous = code;
    worst = std::max(worst, std::abs(double(decode_exponent(code)) / n - 1.0));
  }
  EXPECT_LE(worst, bound * (1 + 1e-5));
  EXPECT_GT(worst, 0.95 * bound);
  EXPECT_EQ(encode_exponent(0.f), 0u);  // clamped, not NaN
  EXPECT_EQ(encode_exponent(1e9f), 255u);
  EXPECT_FLOAT_EQ(decode_exponent(0), 1.f);
  EXPECT_FLOAT_EQ(decode_exponent(255), 8192.f);
}

// ---- depth --------------------------------------------------------------------------------

namespace {

// A camera away from the origin (so world coordinates are not trivially small), near 0.1 m,
// far 1000 m, as in the design notes' depth comparison.
FrameCamera depth_test_camera(DepthFormat format) {
  Camera c;
  c.znear = 0.1f;
  c.zfar = 1000.f;
  c.yfov = 0.8f;
  c.world = glm::inverse(glm::lookAt(glm::vec3(3, 2, 5), glm::vec3(0, 0, -10), glm::vec3(0, 1, 0)));
  return camera_for(format, frame_camera(c, 16.f / 9.f));
}

struct ReconstructionError {
  double worst_m = 0;         // largest |reconstructed - true|
  double worst_over_bound = 0;  // largest error / the stated bound for this format
};


ReconstructionError reconstruction_error(DepthFormat format, float distance) {
  FrameCamera camera = depth_test_camera(format);
  glm::mat4 vp = camera.view_projection(), inverse = precise_inverse(vp);
  ReconstructionError e;
  for (int i = 0; i < 2000; ++i) {  // points over the whole view at about `distance` along the axis
    float u = (i % 50) / 49.f * 1.6f - 0.8f, v = (i / 50) / 39.f * 0.8f - 0.4f;
    glm::vec3 dir = glm::normalize(glm::vec3(u, v, -1.f));
    float t = distance * (1.f + 0.01f * float(i % 7) / 7.f) / -dir.z;
    glm::vec3 world = glm::vec3(glm::inverse(camera.view) * glm::vec4(dir * t, 1.f));
    glm::vec4 clip = vp * glm::vec4(world, 1.f);
    float stored = stored_depth(format, window_depth(format, vp, world));
    glm::vec3 back = reconstruct_position(format, inverse, glm::vec2(clip) / clip.w, stored);
    double axial = -(glm::dmat4(camera.view) * glm::dvec4(world, 1)).z;
    double range = glm::length(glm::dvec3(world) - glm::dvec3(camera.position));
    double err = glm::length(glm::dvec3(back) - glm::dvec3(world));
    e.worst_m = std::max(e.worst_m, err);
    e.worst_over_bound = std::max(e.worst_over_bound, err / reconstruction_error_bound(format, camera.znear, camera.zfar, axial, range,
                                                                                  glm::length(glm::dvec3(world))));
  }
  return e;
}

}  // namespace

TEST(Depth, ReversedProjectionPutsNearAtOneAndFarAtZero) {
  FrameCamera standard = depth_test_camera(DepthFormat::D24S8), reversed = depth_test_camera(DepthFormat::D32FS8Reversed);
  glm::vec3 eye = standard.position, forward = -glm::vec3(glm::inverse(standard.view)[2]);
  auto depth = [&](DepthFormat f, const FrameCamera& c, float d) { return window_depth(f, c.view_projection(), eye + forward * d); };
  EXPECT_NEAR(depth(DepthFormat::D24S8, standard, 0.1f), 0.0, 1e-5);
  EXPECT_NEAR(depth(DepthFormat::D24S8, standard, 1000.f), 1.0, 1e-5);
  EXPECT_NEAR(depth(DepthFormat::D32FS8Reversed, reversed, 0.1f), 1.0, 1e-5);
  EXPECT_NEAR(depth(DepthFormat::D32FS8Reversed, reversed, 1000.f), 0.0, 1e-7);
  // Only the z row differs: x, y and w (so the pixels a triangle covers) are identical.
  for (int row : {0, 1, 3})
    for (int col = 0; col < 4; ++col) EXPECT_EQ(standard.projection[col][row], reversed.projection[col][row]);
}

TEST(Depth, ReconstructionWithinItsBoundNearAndFarForEveryFormat) {
  for (DepthFormat f : {DepthFormat::D24S8, DepthFormat::D32FS8, DepthFormat::D32FS8Reversed})
    for (float d : {0.2f, 1.f, 10.f, 50.f, 200.f, 900.f}) {
      ReconstructionError e = reconstruction_error(f, d);
      EXPECT_LE(e.worst_over_bound, 1.0) << depth_format_name(f) << " at " << d << " m: " << e.worst_m << " m";
    }
}

TEST(Depth, StandardDepthErrorGrowsWithTheSquareOfDistance) {
  // Depth steps are spent near the camera: a step is worth d^2 (f - n) / (n f) metres.
  double at_50 = reconstruction_error(DepthFormat::D24S8, 50.f).worst_m;
  double at_200 = reconstruction_error(DepthFormat::D24S8, 200.f).worst_m;
  EXPECT_GT(at_200 / at_50, 16 * 0.5);
  EXPECT_LT(at_200 / at_50, 16 * 2.0);
  EXPECT_GT(at_200, 0.01) << "D24 at 200 m (near 0.1 m): centimetres";
}

TEST(Depth, ReversedZBeatsStandardD24AtDistance) {
  for (float d : {10.f, 50.f, 200.f, 900.f}) {
    double d24 = reconstruction_error(DepthFormat::D24S8, d).worst_m;
    double reversed = reconstruction_error(DepthFormat::D32FS8Reversed, d).worst_m;
    EXPECT_LT(reversed * 20, d24) << d << " m";
    EXPECT_LT(reversed / d, 1e-6) << "reversed-Z keeps float's relative precision at " << d << " m";
  }
  // Standard D32F gains nothing over D24: near 1 a float has no more bits than 24.
  double d32 = reconstruction_error(DepthFormat::D32FS8, 200.f).worst_m, d24 = reconstruction_error(DepthFormat::D24S8, 200.f).worst_m;
  EXPECT_GT(d32, 0.5 * d24);
}

TEST(Layouts, BytesPerPixel) {
  EXPECT_EQ(bytes_per_pixel(our_layout()), 16u);    // 4 + 4 + 4 + D24S8 4
  EXPECT_EQ(bytes_per_pixel(source_layout()), 20u); // the thesis: 4 + 4 + 4 + R32F 4 + D24S8 4
  EXPECT_EQ(bytes_per_pixel(layout_named("oct8")), 14u);
  EXPECT_EQ(bytes_per_pixel(float_layout()), 16u * 4 + 4);
  EXPECT_THROW(layout_named("nope"), std::exception);
  for (const auto& l : layouts()) {
    std::size_t sum = 0;
    for (const auto& t : targets(l)) sum += t.bytes;
    EXPECT_EQ(sum, bytes_per_pixel(l)) << l.name;
  }
}
