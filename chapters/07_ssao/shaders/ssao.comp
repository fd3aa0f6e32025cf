#version 450
// Chapter 07's ambient occlusion from the G-buffer, one invocation per AO texel: the classic
// algorithm (AO_CLASSIC) or the source's 2D-disk method with Bunnell's term (AO_DISK). The C++
// twin of every formula here is ao_math.h. Writes A in [0, 1], 1 where nothing occludes (and
// for the sky).
layout(local_size_x = 8, local_size_y = 8) in;
#include "02_gbuffer/shaders/gbuffer.glsl"

layout(r32f, binding = 0) uniform writeonly image2D u_out;

uniform mat4 u_view, u_projection;
uniform int u_samples;
uniform float u_radius;             // R, world units
uniform int u_scale;                // 1, 2 or 4: AO texel (x, y) stands for G-buffer pixel scale * (x, y) + scale / 2
uniform int u_noise_on;
uniform float u_bias;               // x R
uniform float u_max_screen_radius;  // disk: at most this fraction of the image height
uniform vec4 u_kernel[128];
uniform vec4 u_noise[16];

const float PI = 3.14159265358979;

// A right-handed orthonormal basis around unit n (Duff et al. 2017): ao_math's twin.
void basis(vec3 n, out vec3 t, out vec3 b) {
  float sign_z = n.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (sign_z + n.z);
  float c = n.x * n.y * a;
  t = vec3(1.0 + sign_z * n.x * n.x * a, sign_z * c, -sign_z * n.x);
  b = vec3(c, sign_z + n.y * n.y * a, -n.y);
}

bool sky_depth(float depth) { return depth == gb_depth_info.z; }
vec3 world_at(ivec2 pixel, float depth) { return reconstruct_position(vec2(pixel) + 0.5, depth); }
float view_depth(vec3 world) { return -(u_view * vec4(world, 1.0)).z; }

#ifdef AO_CLASSIC
// [classic]
float classic_ao(ivec2 pixel, Surface s) {
  vec3 p = (u_view * vec4(s.position, 1.0)).xyz;  // view space: the camera looks down -z
  vec3 t, b;
  basis(s.normal, t, b);                           // the tangent frame, in world space
  vec3 r = u_noise[(pixel.x & 3) + 4 * (pixel.y & 3)].xyz;
  float hidden = 0.0;
  for (int i = 0; i < u_samples; ++i) {
    vec3 k = u_kernel[i].xyz;
    if (u_noise_on != 0) k = k - 2.0 * dot(k, r) * r;  // reflect: the height above the surface stays
    vec3 offset = k.x * t + k.y * b + k.z * s.normal;  // world space
#ifdef AO_TUTORIAL_BUG
    vec3 q = p + u_radius * offset;                    // the bug: a world offset on a view-space point
#else
    vec3 q = p + u_radius * (mat3(u_view) * offset);   // both in view space
#endif
    vec4 clip = u_projection * vec4(q, 1.0);
    if (clip.w <= 0.0) continue;
    vec2 ndc = clip.xy / clip.w;
    if (any(greaterThan(abs(ndc), vec2(1.0)))) continue;  // off the screen: nothing known, counts as open
    ivec2 sp = clamp(ivec2((ndc * 0.5 + 0.5) * gb_size.xy), ivec2(0), ivec2(gb_size.xy) - 1);
    float depth = texelFetch(gb_depth, sp, 0).r;
    if (sky_depth(depth)) continue;
    float scene = view_depth(world_at(sp, depth));  // what the depth buffer holds there
    float sample_depth = -q.z;
    // hidden when the stored surface is in front of the point; the range check fades
    // occluders far in front of the pixel (a column before a distant wall)
    float range = smoothstep(0.0, 1.0, u_radius / max(abs(-p.z - scene), 1e-6));
    hidden += (scene <= sample_depth - u_bias * u_radius ? 1.0 : 0.0) * range;
  }
  return 1.0 - hidden / float(u_samples);
}
// [/classic]
#endif

#ifdef AO_DISK
// [disk]
float disk_ao(ivec2 pixel, Surface s) {
  float zr = view_depth(s.position);
  // R projected at the receiver's depth, in pixels, clamped near the camera
  float scale_px = u_projection[1][1] * 0.5 * gb_size.y / zr;  // pixels per world unit at depth zr
  float radius_px = min(u_radius * scale_px, u_max_screen_radius * gb_size.y);
  float world_radius = radius_px / scale_px;
  // each sample stands for an equal share of the disk: area pi R^2 / N at the receiver's depth
  float share = PI * world_radius * world_radius / float(u_samples);
  float occlusion = 0.0;
  for (int i = 0; i < u_samples; ++i) {
    float rr = sqrt((float(i) + 0.5) / float(u_samples));
    float a = 2.39996323 * float(i);
    ivec2 sp = pixel + ivec2(round(rr * radius_px * vec2(cos(a), sin(a))));
    if (sp == pixel || any(lessThan(sp, ivec2(0))) || any(greaterThanEqual(sp, ivec2(gb_size.xy)))) continue;
    float depth = texelFetch(gb_depth, sp, 0).r;
    if (sky_depth(depth)) continue;
    vec3 e = world_at(sp, depth);
    vec3 v = e - s.position;
    float d2 = dot(v, v);
    if (d2 > u_radius * u_radius || d2 <= 0.0) continue;  // beyond the rays' length R
    vec3 ne = decode_normal(texelFetch(gb_normal, sp, 0));
    float ze = view_depth(e);
    // the share at the emitter's depth, spread over the surface the pixel sees at a slant
    vec3 to_eye = normalize(gb_eye.xyz - e);
    float area = share * (ze / zr) * (ze / zr) / max(abs(dot(ne, to_eye)), 0.2);
    v *= inversesqrt(d2);
#ifdef AO_BUNNELL
    occlusion += (1.0 - inversesqrt(1.0 + area / (PI * d2))) * abs(dot(ne, v)) * clamp(4.0 * dot(s.normal, v), 0.0, 1.0);
#else
    occlusion += area * abs(dot(ne, v)) * max(dot(s.normal, v), 0.0) / (PI * d2 + area);
#endif
  }
  return 1.0 - clamp(occlusion, 0.0, 1.0);
}
// [/disk]
#endif

void main() {
  ivec2 q = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(q, imageSize(u_out)))) return;
  ivec2 pixel = min(q * u_scale + u_scale / 2, ivec2(gb_size.xy) - 1);
  Surface s = decode_gbuffer(pixel);
  float ao = 1.0;
  if (!s.is_sky) {
#ifdef AO_CLASSIC
    ao = classic_ao(pixel, s);
#else
    ao = disk_ao(pixel, s);
#endif
  }
  imageStore(u_out, q, vec4(ao));
}
