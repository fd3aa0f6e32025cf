#include "chapters/05_hdr/exposure_feedback.h"

#include "common/error.h"

namespace lp::ch05 {

namespace {
constexpr GLbitfield kMapping = GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
}

ExposureFeedback::ExposureFeedback(int slots) : slots_(std::size_t(std::max(1, slots))) {
  const auto bytes = GLsizeiptr(slots_.size() * sizeof(ExposureState));
  glNamedBufferStorage(ring_.id(), bytes, nullptr, kMapping);
  mapped_ = static_cast<const ExposureState*>(glMapNamedBufferRange(ring_.id(), 0, bytes, kMapping));
  if (!mapped_) throw Error("could not map the exposure read-back ring persistently");
}

ExposureFeedback::~ExposureFeedback() {
  for (Slot& s : slots_)
    if (s.fence) glDeleteSync(s.fence);
  // Deleting the buffer (ring_) unmaps it.
}

// [read-back]
// The newest slot whose copy the GPU has finished. A timeout of 0 only asks; the flush bit
// makes sure the fence is on its way to the GPU, so it will pass without a later glFlush.
void ExposureFeedback::poll() {
  Slot* newest = nullptr;
  for (Slot& s : slots_) {
    if (!s.fence || (newest && s.frame < newest->frame)) continue;
    GLenum status = glClientWaitSync(s.fence, GL_SYNC_FLUSH_COMMANDS_BIT, 0);
    if (status == GL_ALREADY_SIGNALED || status == GL_CONDITION_SATISFIED) newest = &s;
  }
  if (!newest) return;
  const ExposureState& state = mapped_[newest - slots_.data()];  // coherent: visible once the fence passed
  if (!last_.valid || newest->frame > last_.frame)
    last_ = {.valid = true, .state = state, .frame = newest->frame, .generation = newest->generation, .decay = newest->decay};
  for (Slot& s : slots_)  // it and everything older is done (the GPU works in order)
    if (s.fence && s.frame <= newest->frame) {
      glDeleteSync(s.fence);
      s.fence = nullptr;
    }
}
// [/read-back]

// [in-flight]
// Nothing throttles a CPU that draws without presenting: headless on a fast GPU it runs many
// frames ahead, and a three-slot ring would rarely see a copy finish. So
// the ring is also the limit on frames in flight, as a swap chain's is: when the oldest copy
// is as many frames old as there are slots and still not done, wait for it. The GPU still
// has the frames after it queued and never idles; a reading is never older than that.
void ExposureFeedback::limit_frames_in_flight() {
  Slot* oldest = nullptr;
  for (Slot& s : slots_)
    if (s.fence && (!oldest || s.frame < oldest->frame)) oldest = &s;
  if (!oldest || frame_ - oldest->frame < slots_.size()) return;
  for (;;) {
    GLenum status = glClientWaitSync(oldest->fence, GL_SYNC_FLUSH_COMMANDS_BIT, 1'000'000'000);  // 1 s at a time
    if (status == GL_WAIT_FAILED) throw Error("waiting for the exposure read-back's fence failed");
    if (status != GL_TIMEOUT_EXPIRED) break;
  }
  poll();
}
// [/in-flight]

ExposureEstimate ExposureFeedback::begin_frame(const AdaptationSettings& s, float delta, float start_scale) {
  ++frame_;
  if (s.tau > 0.f) decay_ += double(s.dt) / double(s.tau);
  else last_instant_ = frame_;
  poll();
  limit_frames_in_flight();
  ExposureEstimate e{.exposure = exposure_limit(s, delta, start_scale)};
  // [use-reading]
  // A reading bounds this frame if the eye was not reset since, and every frame after it
  // adapted with a time constant (tau > 0).
  if (last_.valid && last_.generation == generation_ && last_instant_ <= last_.frame && last_.state.adapted > 0.f) {
    float bound = exposure_bound_after(s, last_.state.adapted, decay_ - last_.decay, frame_ - last_.frame);
    if (bound < e.exposure) e = {.exposure = bound, .age = int(frame_ - last_.frame), .read = last_.state.exposure};
  }
  // [/use-reading]
  return e;
}

void ExposureFeedback::end_frame(GLuint state_buffer) {
  // The slot of the oldest copy; if the GPU has not finished it yet, that reading is dropped.
  Slot* slot = &slots_[0];
  for (Slot& s : slots_)
    if (!s.fence) { slot = &s; break; }
    else if (s.frame < slot->frame) slot = &s;
  if (slot->fence) glDeleteSync(slot->fence);
  const auto index = GLintptr(slot - slots_.data());
  // EyeAdaptation::update ended with GL_BUFFER_UPDATE_BARRIER_BIT: the copy sees its writes.
  glCopyNamedBufferSubData(state_buffer, ring_.id(), 0, index * GLintptr(sizeof(ExposureState)), sizeof(ExposureState));
  *slot = {.fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0), .frame = frame_, .generation = generation_,
           .decay = decay_};
}

}  // namespace lp::ch05
