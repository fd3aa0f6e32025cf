# Chapter 09: tiled and clustered light culling. Unit tests of the grid maths (no OpenGL),
# GPU tests on a headless context (the cross-check against chapter 03, counts, hard cases).
lightpass_gtests(09_clustered unit lightpass_09_clustered unit/test_09_clustered.cpp)
lightpass_gtests(09_clustered gl lightpass_09_clustered unit/test_09_clustered_gl.cpp)

# The program: reference images (every mode, inside a light, the heat maps and the grid).
set(P09 $<TARGET_FILE:09_clustered>)
foreach(mode clustered tiled clustered-fragment tiled-fragment stencil)
  lightpass_program_test(09_clustered.reference.${mode} 0 "references match" ${P09} --check --mode ${mode} --out ${CHECK_OUT}/09_clustered)
endforeach()
# A headless run reports what it did: the street's 312 lights, lit pairs equal to the stencil
# volumes' (69 096 at 320x180 on the overview, the same count in both runs), no light dropped.
lightpass_program_test(09_clustered.headless_reports_lit_pairs_and_no_drops 0
  "312 local lights, clustered: .*lights evaluated [0-9]+, lit 69096, .*3456 cells, [1-9][0-9]* list entries.*dropped 0"
  ${P09} --headless --size 320x180 --out ${CMAKE_BINARY_DIR}/out/09_headless.png)
lightpass_program_test(09_clustered.stencil_lights_the_same_pairs 0 "312 local lights, stencil: .*lit 69096,"
  ${P09} --headless --size 320x180 --mode stencil --out ${CMAKE_BINARY_DIR}/out/09_headless_stencil.png)
lightpass_program_test(09_clustered.bad_mode 2 "unknown mode 'forward'" ${P09} --mode forward)
# --bench times the three passes apart, under the names the sweep reads.
lightpass_program_test(09_clustered.bench_times_the_three_passes 0
  "\"name\":\"local lights: clustered: depth bounds\".*\"name\":\"local lights: clustered: assign\".*\"name\":\"local lights: clustered: shade\",[^}]*\"counts\":\\{\"evaluated\":[1-9][0-9]*,\"lit\":[1-9][0-9]*\\}"
  ${P09} --bench --frames 2 --size 160x90)
# A grid too large for its bounds is refused with a message, not allocated.
lightpass_program_test(09_clustered.huge_grid_is_refused 1 "a grid of 1024 x 1024 x 256 cells is more than 4 194 304"
  ${P09} --headless --size 1024x1024 --clusters-x 1024 --clusters-y 1024 --slices 256 --out ${CMAKE_BINARY_DIR}/out/09_huge.png)
# The window path (GLFW + the panel) under a virtual X display, closing itself after 3 frames.
# A smoke test: at 320x180 the panel covers most of the window, so the lit fraction says the
# window drew, not that the street is under it (the references check the street).
lightpass_image_test(09_clustered.window_smoke_screenshot "window screenshot, 320x180" ${CMAKE_BINARY_DIR}/out/09_window.png
  --size 320x180 --background ${BACKGROUND_SRGB8} --lit 0.3 1
  RUN xvfb-run -a -s "-screen 0 320x180x24" ${P09} --size 320x180 --frames 3 --out ${CMAKE_BINARY_DIR}/out/09_window.png)
# Clustered forward: the opaque street drawn forward from the cluster lists equals the deferred.
lightpass_gtests(09_clustered_forward gl lightpass_09_clustered unit/test_09_clustered_forward_gl.cpp)
