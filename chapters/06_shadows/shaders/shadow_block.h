// [shadow-block]
// What the visibility hook knows of the shadow maps, written once for both languages: GLSL
// includes this file in shadow_visibility.glsl (the uniform block ShadowBlock), C++ in
// shadow_stage.cpp (which fills it), each with its own vec4 and mat4. std140: every vec4 and
// mat4 starts on 16 bytes and the floats fill the lines between (shadow_stage.cpp asserts the
// offsets).
#define SHADOW_MAX_POISSON_TAPS 64
struct ShadowParameters {
  mat4 matrix;           // world to the sun map's clip space (orthographic)
  float texel_metres;    // one map texel, metres
  float depth_range;     // the map's depth range, metres (window depth 1 is this far)
  float map_size;        // texels a side
  float pcf_radius;      // PCF: the kernel's radius in texels, k / 2
  float constant_bias;   // texels (shadow_math.h [bias])
  float slope_bias;      // texels per unit of tan(theta)
  float normal_offset;   // texels
  float min_variance;    // VSM, in window depth squared
  float esm_c;           // ESM's exponent
  float vsm_p_min;       // VSM's light-bleeding reduction
  float poisson_taps;    // PCF and PCSS: taps of the Poisson disk (0: PCF's k x k grid)
  float unused0;
  mat4 view;             // world to the light's view space (looking down -z)
  vec2 extent;           // the map's box: width and height, metres
  float unused1;
  float tan_sun_radius;  // PCSS: tan(the sun's angular radius)
  vec4 poisson[SHADOW_MAX_POISSON_TAPS / 2];  // the unit-disk taps, two a vec4 (xy, zw)
  mat4 spot_matrix;      // world to the marked spot light's clip space (perspective)
  mat4 spot_view;        // world to its view space (looking down -z)
  vec3 spot_position;
  float spot_mapped;     // 1 when the spot's map was drawn this frame
  float spot_near, spot_far, spot_tan_cone, spot_map_size;  // its frustum (metres) and map (texels)
};
// [/shadow-block]
