// Chapter 06: the visibility hook with the vsm method (shadow_visibility.glsl).
#define SHADOW_METHOD SHADOW_VSM
#include "06_shadows/shaders/shadow_visibility.glsl"
