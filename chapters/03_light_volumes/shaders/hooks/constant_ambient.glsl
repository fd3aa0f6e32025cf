// The frame's ambient hook, chapter 03's own: the scene's one constant ambient light for
// every pixel. Chapter 03's global pass includes the file that the define FRAME_AMBIENT
// names; chapters 07 and 08 name theirs (ambient occlusion, indirect light) instead.
vec3 ambient_light(vec3 ambient, Surface s, ivec2 pixel) { return ambient; }
