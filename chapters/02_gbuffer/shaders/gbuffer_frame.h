// [frame-block]
// The members of the G-buffer's per-frame uniform block (std140), written once for both
// languages: gbuffer.glsl declares `uniform GBufferFrame { ...this file... }` and gbuffer.h
// `struct GBufferFrame { ...this file... }` (mat4 and vec4 are glm's there), so the C++ that
// fills the block and the GLSL that reads it cannot drift.
#define GBUFFER_PALETTE_SIZE 256  // emissive codes: 0 = none, 1..255 materials
mat4 gb_view_projection;                 // the camera the G-buffer was drawn with
mat4 gb_inverse_view_projection;         // computed in double precision on the CPU
vec4 gb_eye;                             // xyz: camera position (world)
vec4 gb_size;                            // width, height, 1 / width, 1 / height
vec4 gb_depth_info;                      // near, far, the depth value meaning "sky", 1 if reversed-Z
vec4 gb_emissive[GBUFFER_PALETTE_SIZE];  // rgb: emissive colour of palette code i
// [/frame-block]
