# Chapter 01: the lighting model on the CPU, the forward renderer on a headless context, and
# the program itself (reference images, outputs and bad input).
lightpass_gtests(01_forward unit lightpass_01_forward unit/test_lighting.cpp)
lightpass_gtests(01_forward gl lightpass_01_forward unit/test_forward_gl.cpp unit/test_01_twins_gl.cpp unit/glsl_twin.cpp)

set(P01 $<TARGET_FILE:01_forward>)
foreach(mode per-pixel per-vertex unnormalized multi-pass)
  lightpass_program_test(01_forward.reference.${mode} 0 "references match" ${P01} --check --mode ${mode} --out ${CHECK_OUT}/01_forward)
endforeach()
# The headless path writes the image --check compares: the default view and mode at the
# references' size equal overview_per-pixel.png (within --check's 3 steps on 0.1 %).
lightpass_image_test(01_forward.headless_matches_the_reference "wrote .*01_headless.png" ${CMAKE_BINARY_DIR}/out/01_headless.png
  --matches ${CMAKE_SOURCE_DIR}/tests/reference/01_forward/overview_per-pixel.png
  RUN ${P01} --headless --size 320x180 --out ${CMAKE_BINARY_DIR}/out/01_headless.png)
lightpass_program_test(01_forward.no_display_falls_back 0 "no display.*rendering headless"
  env -u DISPLAY -u WAYLAND_DISPLAY ${P01} --size 160x90 --out ${CMAKE_BINARY_DIR}/out/01_nodisplay.png)
lightpass_program_test(01_forward.bench_prints_json 0 "\"passes\":\\[\\{\"name\":\"forward: all lights in one pass\""
  ${P01} --bench --frames 2 --size 160x90)
add_test(NAME 01_forward.unknown_option COMMAND ${EXPECT} 2 "unknown option '--frobnicate'" "^usage: 01_forward" -- ${P01} --frobnicate)
lightpass_program_test(01_forward.zero_size 2 "has no pixels" ${P01} --headless --size 0x0)
lightpass_program_test(01_forward.bad_size 2 "expects WxH" ${P01} --headless --size big)
lightpass_program_test(01_forward.bad_mode 2 "unknown mode 'shiny'" ${P01} --mode shiny)
lightpass_program_test(01_forward.bad_knob 2 "--lights must be between" ${P01} --lights -3)
lightpass_program_test(01_forward.unknown_view 1 "no camera named 'nowhere'. views: overview" ${P01} --headless --view nowhere)
# A mismatch writes the difference as a heat map with its key (a colour bar and its scale) below.
add_test(NAME 01_forward.check_difference_has_a_key
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/mismatch_key.sh ${P01} $<TARGET_FILE:image_stats> ${CMAKE_SOURCE_DIR} ${CMAKE_BINARY_DIR}/mismatch_key)
# Both places a relative --scene is looked for are named: the current directory, then the source root.
lightpass_program_test(01_forward.missing_scene 1 "cannot open scene 'nothing.gltf': no such file in the current directory [(]/.*/nothing.gltf[)] nor under the source root [(]/.*/nothing.gltf[)]"
  ${P01} --headless --scene nothing.gltf)
add_test(NAME 01_forward.list_names_the_knobs COMMAND ${EXPECT} 0 "^knobs:$" "^  --lights N +lights to use .*default 0[)]$" -- ${P01} --list)
lightpass_program_test(01_forward.malformed_scene 1 "cannot load scene .*malformed.gltf" ${P01} --headless --scene tests/data/malformed.gltf)
lightpass_program_test(01_forward.no_camera 0 "no_camera.gltf has no camera: rendering view 'auto'"
  ${P01} --headless --size 64x36 --scene tests/data/no_camera.gltf --out ${CMAKE_BINARY_DIR}/out/01_no_camera.png)
lightpass_program_test(01_forward.missing_texture_warns 0 "warning: .*could not be loaded.*fallback"
  ${P01} --headless --size 160x90 --scene tests/data/missing_texture.gltf --out ${CMAKE_BINARY_DIR}/out/01_missing_texture.png)
# A mesh without indices or normals (flat normals are made): the cube is drawn and lit, 7.9 % of
# the image on llvmpipe (a missing cube: 0 %, a NaN-black one fails the mean); mean 45.6 steps
# against the background's 39-44.
lightpass_image_test(01_forward.nonindexed_scene_draws_the_cube "wrote" ${CMAKE_BINARY_DIR}/out/01_nonindexed.png
  --background ${BACKGROUND_SRGB8} --lit 0.05 0.12 --mean 43 50
  RUN ${P01} --headless --size 160x90 --scene tests/data/nonindexed_nonormals.gltf --out ${CMAKE_BINARY_DIR}/out/01_nonindexed.png)
# A missing shader: a source root with the assets but no chapters/ folder.
file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/root_without_shaders)
file(CREATE_LINK ${CMAKE_SOURCE_DIR}/assets ${CMAKE_BINARY_DIR}/root_without_shaders/assets SYMBOLIC)
lightpass_program_test(01_forward.missing_shader 1 "cannot open shader '.*root_without_shaders/chapters/01_forward/shaders/forward.vert': no such file"
  env LIGHTPASS_ROOT=${CMAKE_BINARY_DIR}/root_without_shaders ${P01} --headless --size 64x36)
add_test(NAME 01_forward.shader_error_names_file_and_line
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/shader_error.sh ${P01} ${CMAKE_SOURCE_DIR} ${CMAKE_BINARY_DIR}/shader_error_root)

# The window's input at 0.7 fps (every frame slowed by a test hook): taps and clicks shorter than
# a frame, sent by xdotool, are queued and handled in order: P saves numbered files, R says
# which file and line failed and then that it reloaded, two clicks pick a mode, Esc closes.
add_test(NAME 01_forward.window_input_at_a_slow_frame_rate
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/window_input.sh ${P01} ${CMAKE_SOURCE_DIR} ${CMAKE_BINARY_DIR}/window_input)
set_tests_properties(01_forward.window_input_at_a_slow_frame_rate PROPERTIES TIMEOUT 300)
# The panel's frame time and rate, CPU and GPU (llvmpipe's on the software renderer): with
# every frame made 300 ms long, the CPU time it shows is at least that, and the GPU's is known.
add_test(NAME 01_forward.window_panel_shows_the_frame_times
  COMMAND ${EXPECT} 0 "^test: frame 6 presented [(]the panel shows (3[0-9][0-9]|[4-9][0-9][0-9]|[0-9][0-9][0-9][0-9]+)[.][0-9] ms CPU [(][0-9.]+ fps[)], [0-9]+[.][0-9] ms (llvmpipe|GPU) [(][0-9.]+ fps[)][)]$"
  -- env LIGHTPASS_TEST_SLOW_FRAME_MS=300 xvfb-run -a -s "-screen 0 320x180x24" ${P01} --size 320x180 --frames 6)
set_tests_properties(01_forward.window_panel_shows_the_frame_times PROPERTIES TIMEOUT 300)
# --exercise K in the window (Xvfb): the reader's file is what is drawn (the solution's and the
# stub's snapshots differ, the solution's twice are equal), R after an edit reloads it, a mistake
# in it is named by that file and line, at R and at the start (exit 1).
add_test(NAME 01_forward.window_exercise_draws_and_reloads_the_readers_file
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/window_exercise.sh ${P01} ${CMAKE_SOURCE_DIR} ${CMAKE_BINARY_DIR}/window_exercise)
set_tests_properties(01_forward.window_exercise_draws_and_reloads_the_readers_file PROPERTIES TIMEOUT 300)
# The window path (GLFW + the panel) under a virtual X display, closing itself after 3 frames.
# The screenshot is the scene under the panel, not a black window: 54 % of it is lit on
# llvmpipe (the scene alone: 59 %, the background alone: 0).
lightpass_image_test(01_forward.window_screenshot "window screenshot, 640x360" ${CMAKE_BINARY_DIR}/out/01_window.png
  --size 640x360 --background ${BACKGROUND_SRGB8} --lit 0.3 1
  RUN xvfb-run -a -s "-screen 0 640x360x24" ${P01} --size 640x360 --frames 3 --out ${CMAKE_BINARY_DIR}/out/01_window.png)

# The chapter's exercises (main.cpp's list; the book's "Exercises"): solutions pass, stubs fail.
lightpass_exercise_tests(01_forward 3)
# An exercise folder without the file (LIGHTPASS_EXERCISE_DIR names the folder): the path tried, exit 1.
file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/empty_exercises)
lightpass_program_test(01_forward.exercise_missing_file_is_named 1 "exercise .*: no file .*empty_exercises/blinn_phong.glsl [(]LIGHTPASS_EXERCISE_DIR"
  env LIGHTPASS_EXERCISE_DIR=${CMAKE_BINARY_DIR}/empty_exercises ${P01} --exercise 1 --check)
# A reader's shader error names the reader's file and line (through the computed include).
lightpass_program_test(01_forward.exercise_shader_error_names_the_file 1 "bad_exercise/blinn_phong.glsl:3:[0-9]*: error"
  env LIGHTPASS_EXERCISE_DIR=${CMAKE_SOURCE_DIR}/tests/exercises/bad_exercise ${P01} --exercise 1 --check)
