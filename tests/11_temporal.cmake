# Chapter 11: time. The jitter and the paths (unit), GPU tests of the motion vectors and TAA
# (unit/test_11_temporal_gl.cpp), and the program's bad input.
lightpass_gtests(11_temporal unit lightpass_11_temporal unit/test_11_temporal.cpp)
lightpass_gtests(11_temporal gl lightpass_11_temporal unit/test_11_temporal_gl.cpp unit/test_11_twins_gl.cpp unit/glsl_twin.cpp)

set(P11 $<TARGET_FILE:11_temporal>)
lightpass_program_test(11_temporal.bad_path 2 "path" ${P11} --path fly)
lightpass_program_test(11_temporal.path_the_scene_lacks 1 "no camera path named walk for the scene assets/cornell"
  ${P11} --headless --size 160x90 --scene assets/cornell/cornell.gltf --path walk --out ${CMAKE_BINARY_DIR}/out/11_cornell.png)
lightpass_program_test(11_temporal.headless_path_writes_a_strip 0 "wrote a strip of 2 frames"
  ${P11} --headless --size 160x90 --path walk --frames 4 --strip 2 --ao 0 --indirect 0 --show image --out ${CMAKE_BINARY_DIR}/out/11_walk.png)
# The references (tests/reference/11_temporal/, made on llvmpipe and looked at): the first frame,
# the walk's frame 12 with TAA, without, and where TAA dropped its history; the opening.
lightpass_program_test(11_temporal.reference.street_shop 0 "5 of 5 references match" ${P11} --check --out ${CHECK_OUT}/11_temporal)
# The opening (./run 11 with nothing given) shows TAA: the shop window's middle magnified four
# times, without AA beside TAA settled over 16 frames. Against the 16-frame supersampled truth of
# the same view, magnified the same way (--show truth), both halves below the captions are that
# crop (mean within 8 steps; 3.7 and 3.9 on llvmpipe: a split of another view or of the whole
# image is tens of steps off), and on the truth's edge pixels the TAA half is nearer it than the
# no-AA half: at most 0.9 times the error (0.82 on llvmpipe; the TAA half unsettled, one
# jittered frame, is 1.15, and a half without TAA 1), a regression bound.
add_test(NAME 11_temporal.opening_truth COMMAND ${P11} --headless --size 320x180 --view shop_window --show truth
         --out ${CMAKE_BINARY_DIR}/out/11_opening_truth.png)
set_tests_properties(11_temporal.opening_truth PROPERTIES FIXTURES_SETUP opening11)
lightpass_image_test(11_temporal.opening_shows_taa_nearer_the_truth_than_no_aa "wrote" ${CMAKE_BINARY_DIR}/out/11_opening.png
  --region 0 14 160 166 --other-at 80 14 --near ${CMAKE_BINARY_DIR}/out/11_opening_truth.png 8
  --region 160 14 160 166 --near ${CMAKE_BINARY_DIR}/out/11_opening_truth.png 8
  --nearer-than 0 14 ${CMAKE_BINARY_DIR}/out/11_opening_truth.png 0.9
  RUN ${P11} --headless --size 320x180 --out ${CMAKE_BINARY_DIR}/out/11_opening.png)
set_tests_properties(11_temporal.opening_shows_taa_nearer_the_truth_than_no_aa PROPERTIES FIXTURES_REQUIRED opening11)
# --show rejected carries its key (issue 29): in the bottom-left corner, on a box of grey 24, a
# red swatch (6x6 px at this size: pure red, mean 85 steps) beside the text saying what red is,
# whose white strokes light 10-60 % of its rows (17 % drawn), and the box's top row above them.
lightpass_image_test(11_temporal.rejected_has_its_key "wrote" ${CMAKE_BINARY_DIR}/out/11_rejected.png
  --background 24,24,24 --region 2 161 6 6 --mean 85 85 --lit 1 1 --region 0 158 200 2 --mean 24 24
  --region 11 161 200 15 --lit 0.1 0.6
  RUN ${P11} --headless --size 320x180 --path walk --at 1 --ao 0 --indirect 0 --show rejected --out ${CMAKE_BINARY_DIR}/out/11_rejected.png)
# The sweep's options (the sweep itself is long on llvmpipe: 16 truth frames per path frame).
lightpass_program_test(11_temporal.sweep_unknown_option 2 "unknown option '--fast'" $<TARGET_FILE:11_temporal_sweep> --fast)
lightpass_program_test(11_temporal.sweep_bad_frames 2 "--frames must be at least 1" $<TARGET_FILE:11_temporal_sweep> --frames 0)
lightpass_program_test(11_temporal.sweep_unknown_method 2 "--methods: no variant named 'TAA, sharp'"
  $<TARGET_FILE:11_temporal_sweep> --methods "TAA, sharp")
# The chapter's exercises (main.cpp's list; the book's "Exercises"): solutions pass, stubs fail,
# and a plausible wrong answer to each (tests/exercises/wrong/11_temporal/) fails.
lightpass_exercise_tests(11_temporal 3 WRONG 1 2 3)
