// The frame's visibility hook, chapter 03's own: every light reaches every surface it
// lights (no shadows). Chapter 03's light shaders include the file that the define
// FRAME_VISIBILITY names; a later chapter names its own file there (deferred_frame.h's
// ShaderHooks) instead of editing these shaders: chapter 06 looks the light up in its shadow
// map. `index` is the light's place in the frame's LightSet: directional lights count in
// LightSet::directional, local lights in light order (points, cones, wide spots).
float directional_visibility(int index, GpuLight light, Surface s) { return 1.0; }
float local_visibility(int index, GpuLight light, Surface s) { return 1.0; }
