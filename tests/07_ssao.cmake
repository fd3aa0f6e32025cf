# Chapter 07: screen-space ambient occlusion. Unit tests of the maths (no OpenGL), GPU tests
# (each method against the ray-traced truth, the hard cases), and the program: references per
# method and the AO view, bad input.
lightpass_gtests(07_ssao unit lightpass_07_ssao unit/test_07_ao_math.cpp)
lightpass_gtests(07_ssao gl lightpass_07_ssao unit/test_07_ssao_gl.cpp unit/test_07_ssao_hard_gl.cpp
  unit/test_07_twins_gl.cpp unit/glsl_twin.cpp)

set(P07 $<TARGET_FILE:07_ssao>)
lightpass_program_test(07_ssao.reference.cornell 0 "11 of 11 references match" ${P07} --check --out ${CHECK_OUT}/07_ssao)
lightpass_program_test(07_ssao.reference.atrium 0 "4 of 4 references match"
  ${P07} --check --scene assets/atrium/atrium.gltf --out ${CHECK_OUT}/07_ssao_atrium)
lightpass_program_test(07_ssao.headless_says_what_it_computed 0 "AO disk, 32 samples, radius 0.5, 160x90, blurred: frame took"
  ${P07} --headless --size 160x90 --mode disk --samples 32 --out ${CMAKE_BINARY_DIR}/out/07_headless.png)
lightpass_program_test(07_ssao.off_runs_no_ao_pass 0 "no AO pass \\(mode off\\)"
  ${P07} --headless --size 160x90 --mode off --out ${CMAKE_BINARY_DIR}/out/07_off.png)
lightpass_program_test(07_ssao.bad_samples 2 "--samples must be between 1 and 128, got 0" ${P07} --samples 0)
lightpass_program_test(07_ssao.bad_radius 2 "--radius must be between 0.01 and 100, got -1" ${P07} --radius -1)
lightpass_program_test(07_ssao.bad_mode 2 "unknown mode 'hbao'" ${P07} --mode hbao)
lightpass_program_test(07_ssao.bad_radii 2 "--radii must be between 1 and 2, got 3" ${P07} --radii 3)
add_test(NAME 07_ssao.sweep_unknown_option COMMAND ${EXPECT} 2 "unknown option '--fast'" -- $<TARGET_FILE:07_ssao_sweep> --fast)

# The opening (./run 07 with nothing given) shows the AO beside the lit image it darkens: with
# the ambient raised ten times (CliSpec::opening), the lit box's middle half beside the AO's,
# captioned. Below the captions, the left half is the lit image's reference there and the right
# half the AO's (--show ao), both moved in from a quarter of the width: an opening without the
# split fails both. In the lit half the classic AO darkens the image by 6.8 steps on average
# against the same opening without AO on llvmpipe; at the scene's own ambient it is 1.3, which
# no reader sees. At least 3 steps: a visible darkening, and an opening without the raised
# ambient fails.
add_test(NAME 07_ssao.opening_without_ao COMMAND ${P07} --headless --size 320x180 --mode off
         --out ${CMAKE_BINARY_DIR}/out/07_opening_off.png)
set_tests_properties(07_ssao.opening_without_ao PROPERTIES FIXTURES_SETUP opening07)
lightpass_image_test(07_ssao.opening_shows_the_ao_beside_the_lit_image "wrote" ${CMAKE_BINARY_DIR}/out/07_opening.png
  --region 0 14 160 166 --other-at 80 14 --matches ${CMAKE_SOURCE_DIR}/tests/reference/07_ssao/front_classic_ambient10.png
  --region 160 14 160 166 --other-at 80 14 --matches ${CMAKE_SOURCE_DIR}/tests/reference/07_ssao/front_classic_show-ao.png
  --region 0 14 160 166 --other-at 0 14 --differs-from ${CMAKE_BINARY_DIR}/out/07_opening_off.png 3
  RUN ${P07} --headless --size 320x180 --out ${CMAKE_BINARY_DIR}/out/07_opening.png)
set_tests_properties(07_ssao.opening_shows_the_ao_beside_the_lit_image PROPERTIES FIXTURES_REQUIRED opening07)

# The chapter's exercises (main.cpp's list; the book's "Exercises"): solutions pass, stubs fail.
lightpass_exercise_tests(07_ssao 3)
