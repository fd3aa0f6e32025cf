// A test hook (LightVolumesGl.TheFrameBindsEachStagesUnitsBeforeTheLights): every light's
// visibility is the one texel of the texture on the unit the frame gave the stage.
layout(binding = TEST_UNIT) uniform sampler2D u_test_visibility;
float directional_visibility(int index, GpuLight light, Surface s) { return texelFetch(u_test_visibility, ivec2(0), 0).r; }
float local_visibility(int index, GpuLight light, Surface s) { return texelFetch(u_test_visibility, ivec2(0), 0).r; }
