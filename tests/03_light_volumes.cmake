# Chapter 03: light volumes with stencil. Unit tests of the maths (no OpenGL), GPU tests on
# a headless context (cross-checks, exact fragment counts), and the program itself.

add_executable(test_03_light_volumes unit/test_03_light_volumes.cpp)
target_link_libraries(test_03_light_volumes PRIVATE lightpass_03_light_volumes GTest::gtest_main)
gtest_discover_tests(test_03_light_volumes DISCOVERY_TIMEOUT 60)

add_executable(test_03_light_volumes_gl unit/test_03_light_volumes_gl.cpp)
target_link_libraries(test_03_light_volumes_gl PRIVATE lightpass_03_light_volumes GTest::gtest_main)
gtest_discover_tests(test_03_light_volumes_gl DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300)

# The program: reference images (every strategy, the hard cases, deferred lighting and the
# book's pictures), outputs and bad input.
set(P03 $<TARGET_FILE:03_light_volumes>)
foreach(mode stencil full-screen scissor front-faces back-faces stencil-bits light-prepass light-prepass-chroma)
  lightpass_program_test(03_light_volumes.reference.${mode} 0 "references match" ${P03} --check --mode ${mode} --out ${CHECK_OUT}/03_light_volumes)
endforeach()
lightpass_program_test(03_light_volumes.headless_says_what_it_shaded 0 "frame took .* ms.*fragments shaded [0-9]+, lit [0-9]+, overshading"
  ${P03} --headless --size 160x90 --out ${CMAKE_BINARY_DIR}/out/03_headless.png)
lightpass_program_test(03_light_volumes.bench_prints_json 0 "\"passes\":\\[\\{\"name\":\"geometry: G-buffer"
  ${P03} --bench --frames 2 --size 160x90 --count 0)
# 100 000 lights still render and say how long the frame took (instanced back faces: the
# stencil strategy's two draws per light take about 10 s on llvmpipe).
lightpass_program_test(03_light_volumes.hundred_thousand_lights 0 "100000 local lights, back-faces: frame took [0-9.]+ ms"
  ${P03} --headless --size 64x36 --lights 100000 --mode back-faces --out ${CMAKE_BINARY_DIR}/out/03_100k.png)
# Zero intensity (left out here), a negative intensity and a negative range (left out by the
# loader, the same in every chapter), a 109-degree spot (drawn with a sphere).
add_test(NAME 03_light_volumes.bad_lights_warn_and_render COMMAND ${EXPECT} 0
  "give no light .*'dark' \\(1\\)" "light 'negative' is left out: its intensity -2" "light 'negative_range' is left out: its range -3"
  "90 degrees or more.*'wide_spot'" "^2 local lights"
  -- ${P03} --headless --size 160x90 --scene chapters/03_light_volumes/testdata/bad_lights.gltf --out ${CMAKE_BINARY_DIR}/out/03_bad_lights.png)
lightpass_program_test(03_light_volumes.bad_mode 2 "unknown mode 'tiled'" ${P03} --mode tiled)
lightpass_program_test(03_light_volumes.bad_show 2 "--show must be between" ${P03} --show 9)
lightpass_program_test(03_light_volumes.no_such_light_to_show 1 "there is no light 5000 to show the stencil mask of \\(312 local lights\\)"
  ${P03} --headless --size 64x36 --show 4 --light 5000 --out ${CMAKE_BINARY_DIR}/out/03_nolight.png)

# The window path (GLFW + the panel) under a virtual X display, closing itself after 3 frames.
lightpass_program_test(03_light_volumes.window_screenshot 0 "window screenshot, 320x180"
  xvfb-run -a -s "-screen 0 320x180x24" ${P03} --size 320x180 --frames 3 --out ${CMAKE_BINARY_DIR}/out/03_window.png)
