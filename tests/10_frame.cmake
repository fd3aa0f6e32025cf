# Chapter 10: the whole frame. So far its transparency: GPU tests of the stage against the
# exact per-pixel order and its hard cases, and the program (references, bad input).
lightpass_gtests(10_frame gl lightpass_10_frame unit/test_10_transparency_gl.cpp)
