# Chapter 09: tiled and clustered light culling. Unit tests of the grid maths (no OpenGL),
# GPU tests on a headless context (the cross-check against chapter 03, counts, hard cases).
lightpass_gtests(09_clustered unit lightpass_09_clustered unit/test_09_clustered.cpp)
lightpass_gtests(09_clustered gl lightpass_09_clustered unit/test_09_clustered_gl.cpp)
