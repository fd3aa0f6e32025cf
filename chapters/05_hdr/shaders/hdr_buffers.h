// The HDR stage's storage buffers and their bindings, written once for both languages:
// hdr_math.glsl includes this file, and so does hdr_buffers.h (inside a namespace where uint is
// std::uint32_t), so the C++ that reads a buffer and the GLSL that writes it cannot drift.
#define LOG_AVERAGE_BINDING 5  // LogAverageResult: what the log-average pass found
#define EXPOSURE_BINDING 6     // ExposureState: adapted luminance and exposure
#define PARTIALS_BINDING 7     // compute reduction: one partial sum per workgroup

// [exposure-state]
struct LogAverageResult {
  float mean_log;  // mean of log(delta + L) over the pixels counted
  float count;     // pixels counted (NaN pixels are not)
  float pad0, pad1;
};

struct ExposureState {
  float target;    // this frame's log-average luminance, exp(mean_log)
  float adapted;   // what the eye is adapted to
  float exposure;  // key / adapted: multiplies the radiance before the curve
  float mean_log;
  float count;
  float pad0, pad1, pad2;
};
// [/exposure-state]

struct Partial {  // the compute reduction's sum of one workgroup
  float sum_log;
  uint count;
};
