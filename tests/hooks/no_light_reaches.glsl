// A test's visibility hook (tests/unit/test_03_light_volumes_gl.cpp): every light blocked
// everywhere, as if every surface were in shadow.
float directional_visibility(int index, GpuLight light, Surface s) { return 0.0; }
float local_visibility(int index, GpuLight light, Surface s) { return 0.0; }
