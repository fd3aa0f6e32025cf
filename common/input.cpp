#include "common/input.h"

#include <algorithm>
#include <utility>

namespace lp {

void InputQueue::push(const InputEvent& event) {
  InputEvent e = event;
  // A button takes the place of the last move before it: GLFW's button callback has no
  // position, and asking for the cursor then gives where it is now, not where it was.
  if (e.kind == InputEvent::Move) {
    pushed_move_ = true;
    pushed_x_ = e.x;
    pushed_y_ = e.y;
  } else if (e.kind == InputEvent::Button && pushed_move_) {
    e.x = pushed_x_;
    e.y = pushed_y_;
  }
  // A burst of motion during a slow frame is one move to where the cursor ended up.
  if (e.kind == InputEvent::Move && !events_.empty() && events_.back().kind == InputEvent::Move) {
    events_.back() = e;
    return;
  }
  if (events_.size() >= kCapacity) {
    ++dropped_;
    return;
  }
  events_.push_back(e);
}

FrameInput InputQueue::next_frame() {
  FrameInput f;
  std::vector<int> keys_changed;
  bool button_changed = false;
  const bool after_release = std::exchange(released_, false);
  while (!events_.empty()) {
    const InputEvent& e = events_.front();
    if (e.kind == InputEvent::Key && e.action != InputEvent::kRepeat) {
      if (std::find(keys_changed.begin(), keys_changed.end(), e.code) != keys_changed.end()) break;
      keys_changed.push_back(e.code);
      if (e.action == InputEvent::kPress) f.keys_pressed.push_back(e.code);
    } else if (e.kind == InputEvent::Button) {
      if (button_changed) break;
      // The frame after a release shows what it did (a list it opened): the next press waits
      // for it, as a reader's eye would.
      if (after_release && e.action == InputEvent::kPress) break;
      button_changed = true;
      released_ = e.action == InputEvent::kRelease;
      if (e.code >= 0 && e.code < int(mouse_down_.size())) mouse_down_[std::size_t(e.code)] = e.action != InputEvent::kRelease;
      mouse_known_ = true;
      mouse_x_ = e.x;
      mouse_y_ = e.y;
    } else if (e.kind == InputEvent::Move) {
      if (button_changed) break;
      mouse_known_ = true;
      mouse_x_ = e.x;
      mouse_y_ = e.y;
    }
    f.events.push_back(e);
    events_.pop_front();
  }
  f.mouse_known = mouse_known_;
  f.mouse_x = mouse_x_;
  f.mouse_y = mouse_y_;
  f.mouse_down = mouse_down_;
  return f;
}

}  // namespace lp
