// A light as the culling and shading passes read it, written once for both languages: GLSL
// includes it in grid.glsl (the Lights and Spots buffers, std430), C++ in clustered_lights.cpp,
// which packs it from chapter 03's light set and asserts its size (no padding). What a pair
// (pixel, light) needs is precomputed here, so that shading a pair does one division.
// Guarded: grid.glsl and light_pair.glsl both include it.
#ifndef CLUSTER_LIGHT_H
#define CLUSTER_LIGHT_H
// Chapter 04's tubes (ClusteredLights::set_tubes) end the light order, from u_first_tube on, in
// the same record: the capsule the assignment bins (start and volume radius, the cut), and the
// end and which tube it is in the tubes' own buffer, where neon_light() finds the rest.
struct ClusterLight {
  vec4 position_radius;      // xyz world position (a tube's start), w the cut
  vec4 radiance_inv_range2;  // rgb colour x intensity, w 1 / range^2 (0: no range): the window without a division;
                             // a tube: xyz its end, w its index in the tubes' buffer
};
// A spot's cone, in its own record: the spots are the last lights before the tubes (points,
// cones, wide spots, tubes), light u_first_spot <= i < u_first_tube reads
// cluster_spots[i - u_first_spot], and a point reads nothing more. Chapter 01's cone t = (dot(-l, dir) - cos outer) / (cos inner - cos outer),
// folded to t = dot(-l, axis) + offset.
struct ClusterSpot {
  vec4 axis_offset;  // xyz: the direction it shines / (cos inner - cos outer), w: -cos outer / (cos inner - cos outer)
};
#endif
