#pragma once
// The window's input, queued: GLFW's callbacks push every key, button, cursor move, scroll and
// character as it happens, and each frame takes its share in order. Dear ImGui 1.86 (Debian's)
// reads the keys and buttons that are down when a frame starts, so a tap that begins and ends
// between two frames (a slow frame: chapter 10 on llvmpipe) would never be seen; here a key or
// button changes at most once per frame, and a click keeps the cursor position it happened at.
// No GLFW or ImGui in here, so the rules are unit-tested (tests/unit/test_input.cpp).
#include <array>
#include <cstddef>
#include <deque>
#include <vector>

namespace lp {

struct InputEvent {
  enum Kind { Key, Button, Move, Scroll, Char };
  // GLFW's action values: a key or button is released (0), pressed (1) or held down (2, keys only).
  enum Action { kRelease = 0, kPress = 1, kRepeat = 2 };
  Kind kind = Key;
  int code = 0;         // Key: GLFW key; Button: GLFW mouse button (0..7); Char: the code point
  int action = kPress;  // Key, Button
  int scancode = 0, mods = 0;  // Key (mods also Button), passed on to ImGui
  double x = 0, y = 0;  // Button, Move: the cursor in window coordinates; Scroll: the offsets
};

// What one frame hands to ImGui and to the program's shortcuts.
struct FrameInput {
  std::vector<InputEvent> events;  // taken from the queue, in the order they happened
  std::vector<int> keys_pressed;   // Key presses among them (not repeats), in order
  bool mouse_known = false;        // a cursor position has been seen (by now, not only this frame)
  double mouse_x = 0, mouse_y = 0; // where the cursor was at the last event taken
  std::array<bool, 8> mouse_down{};  // the buttons' state after the events taken
};

class InputQueue {
 public:
  // Bounded: a stalled program does not grow without limit. Consecutive moves are merged
  // into one as they arrive; past the capacity, new events are dropped and counted.
  static constexpr std::size_t kCapacity = 4096;

  // A Button event takes the position of the Move pushed last (its own, when there was none).
  void push(const InputEvent& e);
  // The next frame's events: in order, up to (not including) the first that would change a
  // key already changed in this frame, or any button after a button changed (one click edge
  // per frame, at its own position); cursor moves after a button change wait for the next
  // frame, so ImGui sees the button at the place it was pressed or released. A press waits one
  // frame more after a release (ImGui draws a list a click opened a frame late).
  FrameInput next_frame();

  std::size_t pending() const { return events_.size(); }
  std::size_t dropped() const { return dropped_; }

 private:
  std::deque<InputEvent> events_;
  std::size_t dropped_ = 0;
  bool released_ = false;     // the last frame released a button
  bool pushed_move_ = false;  // the last move pushed, for the buttons after it
  double pushed_x_ = 0, pushed_y_ = 0;
  bool mouse_known_ = false;
  double mouse_x_ = 0, mouse_y_ = 0;
  std::array<bool, 8> mouse_down_{};
};

}  // namespace lp
