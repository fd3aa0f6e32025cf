// One local light at one surface point: chapter 01's light_incident() and blinn_phong(),
// the light ended at its cut, the visibility hook applied. Chapter 03's light.frag runs it
// for each fragment of a volume; chapter 09's tiled and clustered passes for each light of a
// pixel's list, so that every strategy of both chapters lights with the same code. Needs
// 01_forward/shaders/lighting.glsl, 02_gbuffer/shaders/gbuffer.glsl and FRAME_VISIBILITY
// first. `specular` is blinn_phong()'s, before the surface's specular colour tints it.
void local_light(GpuLight light, float cut, int light_index, Surface s, out vec3 diffuse, out vec3 specular) {
  diffuse = vec3(0.0);
  specular = vec3(0.0);
  // [light-pixel]
  // The light ends at its cut, here as well as in its volume: then every strategy, and any
  // tessellation of the volume, lights exactly the same pixels.
  if (!s.is_sky && distance(light.position_type.xyz, s.position) <= cut) {
    vec3 to_light, radiance;
    light_incident(light, s.position, to_light, radiance);
    radiance *= local_visibility(light_index, light, s);
    blinn_phong(s.normal, normalize(gb_eye.xyz - s.position), to_light, radiance, s.exponent, diffuse, specular);
  }
  // [/light-pixel]
}
