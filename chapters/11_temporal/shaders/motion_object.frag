#version 450
#include "11_temporal/shaders/motion.glsl"

in vec4 v_clip_now;
in vec4 v_clip_then;
out vec4 out_motion;

void main() { out_motion = motion_of(v_clip_now, v_clip_then); }
