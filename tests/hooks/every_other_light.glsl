// A test's visibility hook (tests/unit/test_03_light_volumes_gl.cpp): only the local lights
// with an even index reach a surface (the index is the light's place in light order), and
// every directional light.
float directional_visibility(int index, GpuLight light, Surface s) { return 1.0; }
float local_visibility(int index, GpuLight light, Surface s) { return (index % 2) == 0 ? 1.0 : 0.0; }
