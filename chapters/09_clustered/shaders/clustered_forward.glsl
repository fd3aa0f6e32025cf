// Clustered forward: a forward fragment shader lights its surface from the cluster lists of
// chapter 09's clustered pass, with the same grid, the same lists and the same local_light()
// as the deferred shading (shade.glsl's shade_surface()). The fragment's cluster is its
// tile (gl_FragCoord.xy) and the slice of its view depth. Compile with the defines of
// ClusteredLights::forward_defines() (they include gbuffer.glsl's, for the Surface, the eye and
// the frame block) and bind the lists with ClusteredLights::bind_for_forward(). The lists
// must hold every cluster the forward geometry may touch: ClusterSettings::all_cells.
//
//   Surface s = ...;  // from the material, as geometry.frag would store it
//   vec3 diffuse, specular; uint evaluated, lit;
//   clustered_forward(s, gl_FragCoord.xy, diffuse, specular, evaluated, lit);
//   colour = s.albedo * diffuse + specular;  // chapter 03's composite, for this fragment
#include "09_clustered/shaders/shade.glsl"

#ifndef CLUSTERED
#error "clustered_forward.glsl needs the clustered grid (ClusteredLights::forward_defines())"
#endif

// [clustered-forward]
void clustered_forward(Surface s, vec2 frag_coord, out vec3 diffuse, out vec3 specular, out uint evaluated,
                       out uint lit) {
  shade_surface(s, ivec2(frag_coord), diffuse, specular, evaluated, lit);
}
// [/clustered-forward]
