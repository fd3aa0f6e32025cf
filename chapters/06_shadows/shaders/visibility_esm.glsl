// Chapter 06: the visibility hook with the esm method (shadow_visibility.glsl).
#define SHADOW_METHOD SHADOW_ESM
#include "06_shadows/shaders/shadow_visibility.glsl"
