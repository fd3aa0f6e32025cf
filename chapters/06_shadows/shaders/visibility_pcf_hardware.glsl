// Chapter 06: the visibility hook with the pcf_hardware method (shadow_visibility.glsl).
#define SHADOW_METHOD SHADOW_PCF_HARDWARE
#include "06_shadows/shaders/shadow_visibility.glsl"
