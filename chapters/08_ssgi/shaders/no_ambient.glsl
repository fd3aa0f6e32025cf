// Chapter 08's ambient hook (deferred_frame.h's FRAME_AMBIENT): nothing here. The SSGI pass
// needs the direct diffuse light alone (the light that bounces), so the ambient light is not
// added by chapter 03's global pass but later, by the stage's add_light pass, as A x ambient
// beside the indirect light (shaders/add_indirect.frag).
vec3 ambient_light(vec3 ambient, Surface s, ivec2 pixel) { return vec3(0.0); }
