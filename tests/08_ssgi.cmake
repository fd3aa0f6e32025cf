# Chapter 08: screen-space diffuse interreflection merged with SSAO. Unit tests of the maths (no
# OpenGL), GPU tests (against the ray-traced one-bounce truth, the hard cases), and the program:
# references per mode and view, bad input.
lightpass_gtests(08_ssgi unit lightpass_08_ssgi unit/test_08_gi_math.cpp)
lightpass_gtests(08_ssgi gl lightpass_08_ssgi unit/test_08_ssgi_gl.cpp unit/test_08_twins_gl.cpp unit/glsl_twin.cpp)

set(P08 $<TARGET_FILE:08_ssgi>)
lightpass_program_test(08_ssgi.reference.cornell 0 "17 of 17 references match" ${P08} --check --out ${CHECK_OUT}/08_ssgi)
lightpass_program_test(08_ssgi.reference.atrium 0 "2 of 2 references match"
  ${P08} --check --scene assets/atrium/atrium.gltf --out ${CHECK_OUT}/08_ssgi_atrium)
lightpass_program_test(08_ssgi.headless_says_what_it_computed 0
  "SSGI ssgi, 16 samples, regular, radii 0.5 / 2.5, 1 bounce: frame took"
  ${P08} --headless --size 160x90 --samples 17 --pattern regular --out ${CMAKE_BINARY_DIR}/out/08_headless.png)
lightpass_program_test(08_ssgi.off_runs_no_pass 0 "no SSGI pass \\(mode off\\)"
  ${P08} --headless --size 160x90 --mode off --out ${CMAKE_BINARY_DIR}/out/08_off.png)
# The opening (./run 08 with nothing given) shows the light the surfaces bounce: the lit box's
# middle half beside the indirect light's (x 4), captioned. Below the captions, the left half is
# the lit image's reference there and the right half the indirect light's, both moved in from
# a quarter of the width: an opening without the split, or without the move, fails both.
lightpass_image_test(08_ssgi.opening_shows_the_lit_image_beside_its_indirect_light "wrote" ${CMAKE_BINARY_DIR}/out/08_opening.png
  --region 0 14 160 166 --other-at 80 14 --matches ${CMAKE_SOURCE_DIR}/tests/reference/08_ssgi/front_ssgi.png
  --region 160 14 160 166 --other-at 80 14 --matches ${CMAKE_SOURCE_DIR}/tests/reference/08_ssgi/front_ssgi_show-indirect.png
  RUN ${P08} --headless --size 320x180 --out ${CMAKE_BINARY_DIR}/out/08_opening.png)
lightpass_program_test(08_ssgi.bad_samples 2 "--samples must be between 1 and 128, got 0" ${P08} --samples 0)
lightpass_program_test(08_ssgi.bad_bounces 2 "--bounces must be between 1 and 2, got 3" ${P08} --bounces 3)
lightpass_program_test(08_ssgi.bad_mode 2 "unknown mode 'rtgi'" ${P08} --mode rtgi)
lightpass_program_test(08_ssgi.bad_pattern 2 "--pattern must be one of: regular spiral randomised. got .hexagonal." ${P08} --pattern hexagonal)
add_test(NAME 08_ssgi.sweep_unknown_option COMMAND ${EXPECT} 2 "unknown option '--fast'" -- $<TARGET_FILE:08_ssgi_sweep> --fast)
add_test(NAME 08_ssgi.sweep_bad_only COMMAND ${EXPECT} 2 "--only must be cornell, atrium, pan or fixes .got .street.." -- $<TARGET_FILE:08_ssgi_sweep> --only street)
lightpass_program_test(08_ssgi.headless_says_bitmask_gather 0
  "SSGI ssgi, 16 samples, randomised, radii 0.5 / 2.5, 1 bounce, bitmask gather: frame took"
  ${P08} --headless --size 160x90 --samples 16 --gather bitmask --out ${CMAKE_BINARY_DIR}/out/08_headless_bitmask.png)
lightpass_program_test(08_ssgi.bad_gather 2 "--gather must be one of: disk bitmask. got .horizon." ${P08} --gather horizon)
lightpass_program_test(08_ssgi.headless_says_back_faces 0
  "SSGI ssgi, 16 samples, randomised, radii 0.5 / 2.5, 1 bounce, back-face layer: frame took"
  ${P08} --headless --size 160x90 --samples 16 --back-faces on --out ${CMAKE_BINARY_DIR}/out/08_headless_back_faces.png)
lightpass_program_test(08_ssgi.headless_says_guard_band 0
  "SSGI ssgi, 16 samples, randomised, radii 0.5 / 2.5, 1 bounce, guard band 18 px .frame 196x126.: frame took"
  ${P08} --headless --size 160x90 --samples 16 --guard-band 0.2 --out ${CMAKE_BINARY_DIR}/out/08_headless_guard_band.png)
lightpass_program_test(08_ssgi.bad_back_faces 2 "--back-faces must be one of: off on. got .maybe." ${P08} --back-faces maybe)
lightpass_program_test(08_ssgi.bad_guard_band 2 "--guard-band must be between 0 and 1080, got 2000" ${P08} --guard-band 2000)
lightpass_program_test(08_ssgi.guard_band_beyond_the_gl_limit 1 "--guard-band 1000 px makes the frame 18000x2090, larger than the [0-9]+ pixels a side a frame may have here"
  ${P08} --headless --size 16000x90 --guard-band 1000 --mode off --out ${CMAKE_BINARY_DIR}/out/08_big.png)

# The chapter's exercises (main.cpp's list; the book's "Exercises"): solutions pass, stubs fail.
lightpass_exercise_tests(08_ssgi 3)
