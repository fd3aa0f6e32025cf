// Chapter 06: the visibility hook with the pcf method (shadow_visibility.glsl).
#define SHADOW_METHOD SHADOW_PCF
#include "06_shadows/shaders/shadow_visibility.glsl"
