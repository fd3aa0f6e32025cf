#define SHADOW_MAX_SPOTS 16  // spot_atlas.h's kMaxSpotShadows
// [spot-tile]
// A spot light's perspective frustum (shadow_math.h [spot-frustum]) and its tile of the atlas.
struct SpotTile {
  mat4 matrix;           // world to the spot's clip space (perspective)
  mat4 view;             // world to its view space (looking down -z)
  vec4 position;         // xyz: the light's position; w: 1 when its tile was drawn this frame
  vec4 frustum;          // near and far plane (metres), tan(outer cone), the tile's texels a side
  vec4 tile;             // xy: the tile's lower-left corner in the atlas's (u, v); z: its side
};
// [/spot-tile]
// [shadow-block]
// What the visibility hook knows of the maps, written once for both languages: GLSL includes
// it in shadow_visibility.glsl (uniform block ShadowBlock), C++ in shadow_stage.cpp, which
// fills it and asserts the std140 offsets (vec4 and mat4 on 16 bytes, floats between).
#define SHADOW_MAX_POISSON_TAPS 64
#define SHADOW_MAX_CASCADES 4
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
  float msm_moment_bias; // MSM's pull of the moments towards 0.5
  mat4 view;             // world to the light's view space (looking down -z)
  vec2 extent;           // the map's box: width and height, metres
  float msm_optimized;   // MSM: 1 when the map holds the optimised 16-bit moments
  float tan_sun_radius;  // PCSS: tan(the sun's angular radius)
  vec4 poisson[SHADOW_MAX_POISSON_TAPS / 2];  // the unit-disk taps, two a vec4 (xy, zw)
  // ... the cascades' fields ([shadow-block-cascades]), the point lights' and the spots' tiles
  // in the atlas ([shadow-block-spots])
// [/shadow-block]
// [shadow-block-cascades]
  // Cascades (shadow_math.h [cascades]), when SHADOW_CASCADES > 1: the sun's maps are the layers
  // of an array, each with its frustum; the light's view and depth range are those above.
  mat4 cascade_matrix[SHADOW_MAX_CASCADES];  // world to each cascade's clip space
  vec4 cascade_far;      // the view depth where each cascade ends, metres
  vec4 cascade_texel;    // each cascade's texel, metres
  vec4 cascade_extent;   // each cascade's square, metres a side
  vec4 camera_depth;     // a world point's view depth: dot(camera_depth.xyz, p) + camera_depth.w
  float cascade_count;
  float cascade_band;    // the blend band: the last fraction of a cascade's depth range
  float cascade_near;    // the camera's near plane: where the first cascade begins
  float unused2;
// [/shadow-block-cascades]
// [shadow-block-points]
#define SHADOW_MAX_POINT_LIGHTS 8
  // Point lights' cube maps (cube_math.h): layer i of the cube map array is point light i's.
  vec4 point_light[SHADOW_MAX_POINT_LIGHTS];  // xyz: its position; w: its faces' far plane, metres
                                              // (0: no map this frame, its reach is off screen)
  float point_count;     // lights with a cube map (the first point_count entries)
  float point_map_size;  // texels a face side
  float csm_terms;       // convolution shadow maps: the series' terms (csm_math.h [csm])
  float spot_count;      // spot lights with a tile in the atlas (the first spot_count entries of spot)
// [/shadow-block-points]
// [shadow-block-spots]
  // The marked spot lights, each in its tile of the one spot atlas (shadow_math.h [spot-atlas]).
  SpotTile spot[SHADOW_MAX_SPOTS];
// [/shadow-block-spots]
// [shadow-block-pcss-part]
  // PCSS a part at a time (chapter 11's accumulation): of the Poisson disk's taps, the search and
  // the filter read taps part, part + parts, part + 2 parts, ..., the disk turned by turn radians
  // more. Parts 1, part 0, turn 0: every tap, PCSS as it always was.
  float pcss_part;
  float pcss_parts;
  float pcss_turn;
  float unused3;
// [/shadow-block-pcss-part]
};
