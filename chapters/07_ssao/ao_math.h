#pragma once
// Chapter 07's maths on the CPU, the twin of shaders/ao_math.glsl (which ssao.comp and blur.comp
// include; tests/unit/test_07_twins_gl.cpp holds them together): the
// sample kernels of the classic algorithm (random, and energy-minimised by springs), the
// 4x4 noise that rotates them per pixel by reflection, Bunnell's disk-to-disk occlusion term
// of the 2D-disk method, and the bilateral blur's similarity weight. Unit tests hold these;
// the image tests hold the GLSL.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace lp::ch07 {

// [kernel-rules]
// A kernel point k lives in the unit hemisphere of the tangent frame (z along the normal):
// |k| <= 1 and k.z >= kMinCosine * |k|. The floor keeps points off the tangent plane, where a
// depth buffer's own rounding would make a flat floor occlude itself.
inline constexpr float kMinCosine = 0.15f;
inline constexpr float kMinLength = 0.1f;  // and no point at the centre (it tests the pixel itself)
bool in_kernel_hemisphere(glm::vec3 k, float slack = 1e-5f);
// [/kernel-rules]

// N random points: directions uniform over the hemisphere above kMinCosine, lengths
// lerp(kMinLength, 1, (i / N)^2) so more points lie near the centre (the usual classic kernel).
std::vector<glm::vec3> random_kernel(int samples, std::uint64_t seed);

// The source's energy-minimised kernel: the random kernel's points joined by springs (each
// pair closer than `rest` pushes apart in proportion to rest - distance), relaxed
// `iterations` times and put back into the hemisphere after each step. min_spacing(), each
// iteration, into `spacing` when given (the tests check that it grows).
std::vector<glm::vec3> energy_minimised_kernel(int samples, std::uint64_t seed, int iterations = 100,
                                               std::vector<float>* spacing = nullptr);
float min_spacing(const std::vector<glm::vec3>& points);
glm::vec3 clamp_to_kernel_hemisphere(glm::vec3 k);

// [noise]
// The 4x4 noise tile: unit vectors in the tangent plane (z = 0). Reflecting a kernel point
// about the plane whose normal is r, k - 2 (k.r) r, changes only its x and y: its height above
// the surface and its length stay, so the hemisphere stays about the normal.
std::vector<glm::vec3> noise_tile(std::uint64_t seed);  // 16 vectors, row-major 4x4
inline glm::vec3 reflect_about(glm::vec3 k, glm::vec3 r) { return k - 2.f * glm::dot(k, r) * r; }
// [/noise]

// [bunnell]
// Bunnell's disk-to-disk occlusion (GPU Gems 2, ch. 14), the form of his shader code: a disk
// of area A at distance d along the unit direction v (receiver to emitter) occludes
//   (1 - 1 / sqrt(1 + A / (pi d^2))) * |n_e . v| * clamp(4 n_r . v, 0, 1).
// The first factor is 1 - cos(alpha) for a disk of radius sqrt(A / pi) seen on its axis: the
// fraction of the hemisphere's solid angle it covers, exact on the axis (Bunnell writes A / d^2,
// the same for a disk of area pi A). The emitter's cosine is the disk's foreshortening; we take
// its absolute value because a surface seen in the depth buffer blocks light from either side
// (Bunnell's meshes cast shadows from the back only). The receiver's cosine, times 4 and
// clamped, is Bunnell's: an emitter below the receiver's tangent plane occludes nothing, one a
// little above it counts fully (it stands for a disk, not a point).
float bunnell_occlusion(glm::vec3 receiver, glm::vec3 receiver_normal, glm::vec3 emitter, glm::vec3 emitter_normal,
                        float emitter_area);
// Bunnell's first factor is a share of the hemisphere's SOLID ANGLE (normalised by 2 pi); the
// AO integral weights directions by n . w and normalises by pi. For a small disk his term is
// A / (2 pi d^2) times the cosines: half the disk's form factor. The cosine-weighted twin is
// the disk form factor of radiosity (Wallace et al. 1989), exact for a disk on the axis:
//   A |n_e . v| max(n_r . v, 0) / (pi d^2 + A).
float form_factor_occlusion(glm::vec3 receiver, glm::vec3 receiver_normal, glm::vec3 emitter,
                            glm::vec3 emitter_normal, float emitter_area);
// [/bunnell]

// [bilateral]
// The blur's similarity test (the source's threshold): a neighbour counts (weight 1) when its
// view depth is within `depth_threshold` of the centre's, relative to the centre's, and its
// normal within acos(normal_threshold) of the centre's; otherwise 0. The sky never counts.
float bilateral_weight(float centre_depth, float depth, glm::vec3 centre_normal, glm::vec3 normal,
                       float depth_threshold, float normal_threshold);
// [/bilateral]

// The classic's range check (ssao.comp): an occluder `gap` in depth from the pixel counts fully
// within the radius, and fades as smoothstep(0, 1, radius / |gap|) beyond it.
float range_weight(float radius, float gap);

// GTAO's horizon and arc (ssao.comp; the GLSL in shaders/ao_math.glsl). gtao_horizon: the
// horizon cosine an occluder q gives the receiver p (view space, unit normal and view vector):
// the elevation dot((q - p) / |q - p|, view_vec), blended toward the slice's lowest `low` by
// the falloff's weight clamp(|q - p| falloff_mul + falloff_add, 0, 1), and `low` when q is less
// than min_height above the tangent plane. gtao_arc: a slice's cosine-weighted visibility
// between the view vector and the horizon angle h, for the projected normal at angle n,
//   integral from 0 to h of sin t cos(t - n) dt = (cos n + 2 h sin n - cos(2h - n)) / 4,
// which is the integral of |sin t| cos(t - n) between 0 and h for h of either sign; the two
// sides at the tangent plane, h = n +- pi/2, sum to cos n + n sin n (the open slice).
float gtao_horizon(glm::vec3 p, glm::vec3 q, glm::vec3 normal, glm::vec3 view_vec, float low, float falloff_mul,
                   float falloff_add, float min_height);
float gtao_arc(float h, float n, float cos_n);

// The 2D disk's pattern: sample i of n at radius sqrt((i + 0.5) / n) (equal area per sample)
// and angle i times the golden angle (a spiral that never repeats a direction).
glm::vec2 spiral_point(int i, int n);

}  // namespace lp::ch07
