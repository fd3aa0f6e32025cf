// Chapter 06: the visibility hook with the hard method (shadow_visibility.glsl).
#define SHADOW_METHOD SHADOW_HARD
#include "06_shadows/shaders/shadow_visibility.glsl"
