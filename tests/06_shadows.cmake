# Chapter 06: shadows. Unit tests of the maths (no OpenGL), GPU tests (the methods against
# the ray-traced truth, the hard cases), and the program: references per method, bad input.
lightpass_gtests(06_shadows unit lightpass_06_shadows unit/test_06_shadow_math.cpp)
