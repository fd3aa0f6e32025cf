// The pixel a light hook is evaluated for, in window coordinates (pixel centres at +0.5): a
// fragment shader's gl_FragCoord.xy; a compute shader that lights pixels (chapter 09's
// shade.comp) defines FRAME_PIXEL_COMPUTE before its includes and gets its invocation's
// pixel. A hook that needs the pixel (chapter 06's rotated Poisson disk, its volumes'
// per-pixel visibility) calls frame_pixel(), never gl_FragCoord, so it works in both.
#if defined(FRAME_PIXEL_REMAPPED)  // a compute shader whose invocations take pixels in its own order
ivec2 invocation_pixel();  // defined by that shader (chapter 09's zbin_staged.comp)
vec2 frame_pixel() { return vec2(invocation_pixel()) + 0.5; }
#elif defined(FRAME_PIXEL_COMPUTE)
vec2 frame_pixel() { return vec2(gl_GlobalInvocationID.xy) + 0.5; }
#else
vec2 frame_pixel() { return gl_FragCoord.xy; }
#endif
