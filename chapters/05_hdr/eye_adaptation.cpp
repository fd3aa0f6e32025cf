#include "chapters/05_hdr/eye_adaptation.h"

#include "chapters/05_hdr/hdr_pipeline.h"

namespace lp::ch05 {

EyeAdaptation::EyeAdaptation()
    : update_({{GL_COMPUTE_SHADER, "05_hdr/shaders/adaptation.comp"}}),
      state_(gl::make_buffer(nullptr, sizeof(ExposureState), GL_DYNAMIC_STORAGE_BIT)) {}

void EyeAdaptation::update(GLuint log_average_buffer, const AdaptationSettings& s) {
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLogAverageBinding, log_average_buffer);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kExposureBinding, state_.id());
  update_.use();
  update_.set("u_key", s.key);
  update_.set("u_adapt_floor", s.adapt_floor);
  update_.set("u_tau", s.tau);
  update_.set("u_dt", s.dt);
  update_.set("u_reset", int(reset_));
  update_.set("u_start_scale", start_scale_);
  glDispatchCompute(1, 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  reset_ = false;
}

ExposureState EyeAdaptation::read() const {
  ExposureState s{};
  glGetNamedBufferSubData(state_.id(), 0, sizeof(s), &s);
  return s;
}

}  // namespace lp::ch05
