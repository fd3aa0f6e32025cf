# Chapter 08: screen-space diffuse interreflection merged with SSAO. Unit tests of the maths (no
# OpenGL), GPU tests (against the ray-traced one-bounce truth, the hard cases), and the program:
# references per mode and view, bad input.
lightpass_gtests(08_ssgi unit lightpass_08_ssgi unit/test_08_gi_math.cpp)
lightpass_gtests(08_ssgi gl lightpass_08_ssgi unit/test_08_ssgi_gl.cpp)
