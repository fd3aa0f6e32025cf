# The ray-traced ground truth (common/raytrace.h): on the CPU, and against the rasteriser on
# a headless context. Every test is named raytrace.*, so `ctest -R '^raytrace\.'` runs them.
add_executable(raytrace_tests unit/test_raytrace.cpp)
target_link_libraries(raytrace_tests PRIVATE lightpass_raytrace GTest::gtest_main)
gtest_discover_tests(raytrace_tests TEST_PREFIX raytrace.unit. DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300)

add_executable(raytrace_gl_tests unit/test_raytrace_gl.cpp)
target_link_libraries(raytrace_gl_tests PRIVATE lightpass_raytrace lightpass_02_gbuffer GTest::gtest_main)
gtest_discover_tests(raytrace_gl_tests TEST_PREFIX raytrace.gl. DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300)
