// The window's input queue (common/input.h): whatever happens between two slow frames reaches
// the frames in order, a key or button changes at most once per frame, and a click keeps the
// position it happened at. And P's numbered file names (common/image.h).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "common/image.h"
#include "common/input.h"

using namespace lp;

namespace {
constexpr int kKeyP = 80, kKeyR = 82;  // GLFW_KEY_P, GLFW_KEY_R
InputEvent key(int code, int action) { return {.kind = InputEvent::Key, .code = code, .action = action}; }
InputEvent button(int action, double x, double y) { return {.kind = InputEvent::Button, .code = 0, .action = action, .x = x, .y = y}; }
InputEvent move(double x, double y) { return {.kind = InputEvent::Move, .x = x, .y = y}; }
}  // namespace

TEST(InputQueue, ATapBetweenTwoFramesIsPressedInOneFrameAndReleasedInTheNext) {
  InputQueue q;
  q.push(key(kKeyP, InputEvent::kPress));
  q.push(key(kKeyP, InputEvent::kRelease));
  FrameInput first = q.next_frame();
  ASSERT_EQ(first.events.size(), 1u);
  EXPECT_EQ(first.events[0].action, InputEvent::kPress);
  EXPECT_EQ(first.keys_pressed, std::vector<int>{kKeyP});
  FrameInput second = q.next_frame();
  ASSERT_EQ(second.events.size(), 1u);
  EXPECT_EQ(second.events[0].action, InputEvent::kRelease);
  EXPECT_TRUE(second.keys_pressed.empty());
  EXPECT_EQ(q.pending(), 0u);
}

TEST(InputQueue, DifferentKeysShareAFrameInTheOrderPressed) {
  InputQueue q;
  q.push(key(kKeyR, InputEvent::kPress));
  q.push(key(kKeyP, InputEvent::kPress));
  q.push(key(kKeyR, InputEvent::kRelease));  // R changes again: next frame
  q.push(key(kKeyP, InputEvent::kRelease));
  FrameInput first = q.next_frame();
  EXPECT_EQ(first.keys_pressed, (std::vector<int>{kKeyR, kKeyP}));
  EXPECT_EQ(first.events.size(), 2u);
  FrameInput second = q.next_frame();
  EXPECT_EQ(second.events.size(), 2u);  // both releases
  EXPECT_EQ(q.pending(), 0u);
}

TEST(InputQueue, RepeatsAreNotPresses) {
  InputQueue q;
  q.push(key(kKeyP, InputEvent::kPress));
  q.push(key(kKeyP, InputEvent::kRepeat));
  q.push(key(kKeyP, InputEvent::kRepeat));
  FrameInput f = q.next_frame();
  EXPECT_EQ(f.keys_pressed, std::vector<int>{kKeyP});
  EXPECT_EQ(f.events.size(), 3u);
}

TEST(InputQueue, AClickThenAMoveAwayIsDownAndUpWhereItHappened) {
  InputQueue q;
  q.push(move(100, 50));
  q.push(button(InputEvent::kPress, 100, 50));
  q.push(button(InputEvent::kRelease, 100, 50));
  q.push(move(900, 600));  // the cursor left the panel before the next frame
  FrameInput pressed = q.next_frame();
  EXPECT_TRUE(pressed.mouse_down[0]);
  EXPECT_EQ(pressed.mouse_x, 100);
  EXPECT_EQ(pressed.mouse_y, 50);
  FrameInput released = q.next_frame();
  EXPECT_FALSE(released.mouse_down[0]);
  EXPECT_EQ(released.mouse_x, 100);  // still where it was let go
  EXPECT_EQ(released.mouse_y, 50);
  FrameInput moved = q.next_frame();
  EXPECT_FALSE(moved.mouse_down[0]);
  EXPECT_EQ(moved.mouse_x, 900);
  EXPECT_EQ(moved.mouse_y, 600);
}

TEST(InputQueue, AnEmptyFrameKeepsTheButtonsAndTheCursor) {
  InputQueue q;
  q.push(button(InputEvent::kPress, 10, 20));
  q.next_frame();
  FrameInput held = q.next_frame();
  EXPECT_TRUE(held.events.empty());
  EXPECT_TRUE(held.mouse_known);
  EXPECT_TRUE(held.mouse_down[0]);
  EXPECT_EQ(held.mouse_x, 10);
}

TEST(InputQueue, NoCursorIsKnownBeforeOneIsSeen) {
  InputQueue q;
  EXPECT_FALSE(q.next_frame().mouse_known);
}

TEST(InputQueue, ConsecutiveMovesMergeAndTheQueueIsBounded) {
  InputQueue q;
  for (int i = 0; i < 100000; ++i) q.push(move(i, i));
  EXPECT_EQ(q.pending(), 1u);
  EXPECT_EQ(q.next_frame().mouse_x, 99999);
  for (std::size_t i = 0; i < InputQueue::kCapacity + 10; ++i) q.push({.kind = InputEvent::Char, .code = 'a'});
  EXPECT_EQ(q.pending(), InputQueue::kCapacity);
  EXPECT_EQ(q.dropped(), 10u);
}

TEST(NumberedPath, TakesTheFirstFreeNumberAndNeverAnExistingFile) {
  const auto dir = std::filesystem::temp_directory_path() / ("lightpass_numbered_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto base = dir / "10_frame.png";
  EXPECT_EQ(numbered_path(base), dir / "10_frame-001.png");
  std::ofstream(dir / "10_frame-001.png") << "x";
  std::ofstream(dir / "10_frame-003.png") << "x";
  EXPECT_EQ(numbered_path(base), dir / "10_frame-002.png");
  std::ofstream(dir / "10_frame-002.png") << "x";
  EXPECT_EQ(numbered_path(base), dir / "10_frame-004.png");
  std::filesystem::remove_all(dir);
}

TEST(InputQueue, AButtonTakesThePositionOfTheMoveBeforeIt) {
  InputQueue q;
  q.push(move(80, 107));
  q.push(button(InputEvent::kPress, 500, 300));  // GLFW's cursor now, after the poll: not the click's place
  FrameInput f = q.next_frame();
  EXPECT_TRUE(f.mouse_down[0]);
  EXPECT_EQ(f.mouse_x, 80);
  EXPECT_EQ(f.mouse_y, 107);
}

TEST(InputQueue, APressWaitsAFrameAfterARelease) {
  InputQueue q;
  q.push(button(InputEvent::kPress, 10, 10));
  q.push(button(InputEvent::kRelease, 10, 10));
  q.push(button(InputEvent::kPress, 20, 20));  // in the list the first click opened
  q.push(button(InputEvent::kRelease, 20, 20));
  EXPECT_TRUE(q.next_frame().mouse_down[0]);
  EXPECT_FALSE(q.next_frame().mouse_down[0]);
  FrameInput shows = q.next_frame();  // ImGui places the list
  EXPECT_TRUE(shows.events.empty());
  FrameInput second = q.next_frame();
  EXPECT_TRUE(second.mouse_down[0]);
  EXPECT_EQ(second.mouse_x, 20);
  EXPECT_FALSE(q.next_frame().mouse_down[0]);
}
