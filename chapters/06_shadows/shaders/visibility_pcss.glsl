// Chapter 06: the visibility hook with the pcss method (shadow_visibility.glsl).
#define SHADOW_METHOD SHADOW_PCSS
#include "06_shadows/shaders/shadow_visibility.glsl"
