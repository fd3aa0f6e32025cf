#version 450
// Eye adaptation, one thread: the adapted luminance follows the frame's log-average with
// time constant tau, and the exposure is key / adapted, adapted no further than the floor.
#include "05_hdr/shaders/hdr_math.glsl"

layout(local_size_x = 1) in;
layout(std430, binding = LOG_AVERAGE_BINDING) readonly buffer Result { LogAverageResult frame; };
layout(std430, binding = EXPOSURE_BINDING) buffer State { ExposureState state; };
uniform float u_key, u_adapt_floor, u_tau, u_dt, u_start_scale;
uniform bool u_reset;

void main() {
  // [adaptation]
  // A frame with no valid pixel (all NaN) has no average: keep what the eye had.
  float target = frame.count > 0.0 ? exp(frame.mean_log) : (u_reset ? 1.0 : state.adapted);
  float adapted = u_reset ? target * u_start_scale : adapt(state.adapted, target, u_dt, u_tau);
  state.target = target;
  state.adapted = adapted;
  state.exposure = exposure_for(u_key, adapted, u_adapt_floor);
  // [/adaptation]
  state.mean_log = frame.mean_log;
  state.count = frame.count;
}
