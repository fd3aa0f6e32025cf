#pragma once
// The HDR stage's storage buffers as C++ sees them: the structs and bindings of
// shaders/hdr_buffers.h, the one file the GLSL includes too.
#include <cstdint>

#include "common/gl.h"

namespace lp::ch05 {

namespace glsl {
using uint = std::uint32_t;
#include "chapters/05_hdr/shaders/hdr_buffers.h"
}  // namespace glsl
using glsl::ExposureState;
using glsl::LogAverageResult;
using glsl::Partial;
static_assert(sizeof(LogAverageResult) == 16 && sizeof(ExposureState) == 32 && sizeof(Partial) == 8,
              "std430: floats and uints, four bytes each");

inline constexpr GLuint kLogAverageBinding = LOG_AVERAGE_BINDING, kExposureBinding = EXPOSURE_BINDING,
                        kPartialsBinding = PARTIALS_BINDING;

}  // namespace lp::ch05
