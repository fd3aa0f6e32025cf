// Exercise 3 of chapter 03: the light volumes' instance records, unpacked.
// `./run 03 --exercise 3` lights the street with these functions; add `--check` to compare.
//
// Each volume is drawn with its light's record as per-instance attributes
// (light_instances.h); the light shader lights with chapter 01's GpuLight
// (01_forward/shaders/gpu_light.h): position_type (xyz, type LIGHT_POINT or LIGHT_SPOT),
// direction_range (xyz the spot's direction, w glTF's range), radiance (rgb), spot
// (x cos(outer), y 1 / (cos(inner) - cos(outer))).
//   position_radius: xyz the light's position (w is the volume's cut, not needed here)
//   radiance_range:  rgb colour x intensity, w the range (0: unbounded)
//   direction_cone:  xy the direction in chapter 02's octahedral map (octahedral_unfold()),
//                    zw the spot's two cone numbers, as GpuLight.spot holds them
// A point light has no direction: give it (0, 0, -1).
GpuLight unpack_point(vec4 position_radius, vec4 radiance_range) {
  return GpuLight(vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0));  // no light: write the unpacking
}

GpuLight unpack_spot(vec4 position_radius, vec4 radiance_range, vec4 direction_cone) {
  return GpuLight(vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0));  // no light: write the unpacking
}
