# Chapter 11: time. The jitter and the paths (unit), GPU tests of the motion vectors and TAA
# (unit/test_11_temporal_gl.cpp), and the program's bad input.
lightpass_gtests(11_temporal unit lightpass_11_temporal unit/test_11_temporal.cpp)
lightpass_gtests(11_temporal gl lightpass_11_temporal unit/test_11_temporal_gl.cpp unit/test_11_twins_gl.cpp unit/glsl_twin.cpp)

set(P11 $<TARGET_FILE:11_temporal>)
lightpass_program_test(11_temporal.bad_path 2 "path" ${P11} --path fly)
lightpass_program_test(11_temporal.path_the_scene_lacks 1 "no camera path named walk for the scene assets/cornell"
  ${P11} --headless --size 160x90 --scene assets/cornell/cornell.gltf --path walk --out ${CMAKE_BINARY_DIR}/out/11_cornell.png)
lightpass_program_test(11_temporal.headless_path_writes_a_strip 0 "wrote a strip of 2 frames"
  ${P11} --headless --size 160x90 --path walk --frames 4 --strip 2 --ao 0 --indirect 0 --out ${CMAKE_BINARY_DIR}/out/11_walk.png)
# The references (tests/reference/11_temporal/, made on llvmpipe and looked at): the first frame,
# the walk's frame 12 with TAA, without, and where TAA dropped its history.
lightpass_program_test(11_temporal.reference.street_shop 0 "4 of 4 references match" ${P11} --check --out ${CHECK_OUT}/11_temporal)
# The sweep's options (the sweep itself is long on llvmpipe: 16 truth frames per path frame).
lightpass_program_test(11_temporal.sweep_unknown_option 2 "unknown option '--fast'" $<TARGET_FILE:11_temporal_sweep> --fast)
lightpass_program_test(11_temporal.sweep_bad_frames 2 "--frames must be at least 1" $<TARGET_FILE:11_temporal_sweep> --frames 0)
lightpass_program_test(11_temporal.sweep_unknown_method 2 "--methods: no variant named 'TAA, sharp'"
  $<TARGET_FILE:11_temporal_sweep> --methods "TAA, sharp")
# The chapter's exercises (main.cpp's list; the book's "Exercises"): solutions pass, stubs fail,
# and a plausible wrong answer to each (tests/exercises/wrong/11_temporal/) fails.
lightpass_exercise_tests(11_temporal 3 WRONG 1 2 3)
