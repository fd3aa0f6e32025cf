# Chapter 06: shadows. Unit tests of the maths (no OpenGL), GPU tests (the methods against
# the ray-traced truth, the hard cases), and the program: references per method, bad input.
lightpass_gtests(06_shadows unit lightpass_06_shadows unit/test_06_shadow_math.cpp unit/test_06_shadow_metrics.cpp
                 unit/test_06_cube_math.cpp unit/test_06_csm_math.cpp unit/test_06_spot_atlas.cpp)
lightpass_gtests(06_shadows gl lightpass_06_shadows unit/test_06_shadows_gl.cpp unit/test_06_point_shadows_gl.cpp unit/test_06_csm_gl.cpp
                 unit/test_06_spot_atlas_gl.cpp unit/test_06_hard_cases_gl.cpp unit/test_06_twins_gl.cpp unit/glsl_twin.cpp)

# The program: reference images per method (tests/reference/06_shadows/, made on llvmpipe
# with --check --update-references), what a headless run reports, and bad input.
set(P06 $<TARGET_FILE:06_shadows>)
foreach(mode hard pcf pcf-hardware vsm esm volumes pcss msm csm-fourier)
  lightpass_program_test(06_shadows.reference.${mode} 0 "references match" ${P06} --check --mode ${mode} --out ${CHECK_OUT}/06_shadows)
endforeach()
lightpass_program_test(06_shadows.headless_reports_the_map 0 "sun shadows, pcf: map 512x512 \\(1024 KiB\\), [0-9.]+ cm per texel"
  ${P06} --headless --size 160x90 --map 512 --out ${CMAKE_BINARY_DIR}/out/06_headless.png)
lightpass_program_test(06_shadows.bad_kernel_zero 2 "--kernel must be between" ${P06} --kernel 0)
lightpass_program_test(06_shadows.bad_kernel_even 2 "--kernel must be odd" ${P06} --headless --size 16x16 --kernel 4)
lightpass_program_test(06_shadows.bad_map_zero 2 "--map must be between" ${P06} --map 0)
lightpass_program_test(06_shadows.bad_map_too_large 2 "--map must be between" ${P06} --map 100000)
lightpass_program_test(06_shadows.bad_pmin 2 "--pmin must be between" ${P06} --pmin 1)
lightpass_program_test(06_shadows.bad_c 2 "--c must be between" ${P06} --c 0)
lightpass_program_test(06_shadows.bad_moments 2 "--moments must be 16 or 32, not 20" ${P06} --headless --size 16x16 --moments 20)
lightpass_program_test(06_shadows.bad_taps 2 "--taps must be between 0 and 64, got 65" ${P06} --taps 65)
lightpass_program_test(06_shadows.bad_sun_size 2 "--sun-size must be between 0 and 0.2, got 0.5" ${P06} --sun-size 0.5)
lightpass_program_test(06_shadows.bad_sun 2 "--sun must be between 0 and 1000, got -1" ${P06} --sun -1)
lightpass_program_test(06_shadows.bad_mode 2 "unknown mode 'stencil'" ${P06} --mode stencil)
# Cascades: a filtered map is one layer; the report names each cascade's depth range and texel.
lightpass_program_test(06_shadows.bad_cascades_with_vsm 2 "--cascades 4 needs the mode hard, pcf, pcf-hardware or pcss"
  ${P06} --headless --size 16x16 --mode vsm --cascades 4)
lightpass_program_test(06_shadows.bad_cascades_five 2 "--cascades must be between 1 and 4, got 5" ${P06} --cascades 5)
lightpass_program_test(06_shadows.headless_reports_the_cascades 0 "cascade 3: view depth [0-9.]+ to [0-9.]+ m, [0-9.]+ cm per texel"
  ${P06} --headless --size 64x36 --mode hard --cascades 4 --out ${CMAKE_BINARY_DIR}/out/06_cascades.png)
# Point lights: --points all gives each of the atrium's eight a cube map, and the report says so.
lightpass_program_test(06_shadows.headless_reports_the_cube_maps 0 "point lights: 8 cube maps of 6 x 64x64, 8 drawn this frame"
  ${P06} --headless --size 64x36 --points all --cube 64 --out ${CMAKE_BINARY_DIR}/out/06_points.png)
lightpass_program_test(06_shadows.bad_cube 2 "--cube must be between 16 and 4096, got 8" ${P06} --cube 8)
lightpass_program_test(06_shadows.bad_points 2 "--points must be one of: marked all; got 'some'" ${P06} --points some)
# Spot lights: --spots all gives each of the street's twelve spots a tile of one atlas.
lightpass_program_test(06_shadows.headless_reports_the_spot_atlas 0 "spot lights: 12 tiles of 256x256 in a 1024x1024 atlas, 12 drawn"
  ${P06} --headless --size 64x36 --scene assets/street/street.gltf --spots all --out ${CMAKE_BINARY_DIR}/out/06_spots.png)
lightpass_program_test(06_shadows.bad_spots 2 "--spots must be one of: marked all; got 'some'" ${P06} --spots some)
# The sun is scaled only where the scene asks (the atrium's extras: 4): a model without lights,
# lit by the default rig, keeps its light and does not clip to white (at 4 times, its lit faces do).
set(P06_OUT ${CMAKE_BINARY_DIR}/out/06_scenes)
file(MAKE_DIRECTORY ${P06_OUT})
lightpass_program_test(06_shadows.default_rig_is_not_washed_out 0 "within bounds"
  sh -c "'${P06}' --headless --size 160x90 --scene tests/data/no_camera_no_lights.gltf --out '${P06_OUT}/rig.png' && '$<TARGET_FILE:png_coverage>' '${P06_OUT}/rig.png' --covered 0.05 0.6 --bright-share 0 0.01")
# A reader's model on a floor, without lights or a camera (tests/data/box_on_floor.gltf: a red
# 1 m box on a 6 m floor of grey 0.6): the default rig's key, from the left of and above the
# automatic view, casts a shadow the image shows beside the box (issue 29). Against the same view
# with no shadows (chapter 03's frame: chapter 06's with no stage, bit for bit), the floor pixels
# darkened by a quarter or more (a plain step: the eye notices about 2 %; the key gives most of
# the floor's light, so the umbra drops by more than half) number at least 0.09 times the box's
# pixels: half of the hard shadow's visible area, 96 px beside the box's 534 at 320x180 (0.18,
# ray cast from the rig's key, 50 degrees up, in the automatic view; both counts are the render's
# to the pixel), the other half left to PCF's penumbra at its edges. With the key above the camera
# the shadow lies behind the box: 0 px. No floor pixel reaches 250 of 255: grey 0.6 is not clipped.
lightpass_program_test(06_shadows.default_rig_shadow_shows_beside_a_readers_model 0 "within bounds"
  sh -c "'$<TARGET_FILE:03_light_volumes>' --headless --size 320x180 --scene tests/data/box_on_floor.gltf --out '${P06_OUT}/box_plain.png' && '${P06}' --headless --size 320x180 --scene tests/data/box_on_floor.gltf --out '${P06_OUT}/box.png' && '$<TARGET_FILE:png_coverage>' '${P06_OUT}/box.png' --shadow '${P06_OUT}/box_plain.png' 0.09 0.25 --floor-below 250")
lightpass_program_test(06_shadows.atrium_asks_for_its_sun_scale 0 "directional lights x4, as atrium.gltf asks"
  ${P06} --headless --size 64x36 --out ${P06_OUT}/atrium.png)
lightpass_program_test(06_shadows.scene_without_sun 1 "no directional light" ${P06} --headless --size 16x16 --scene tests/data/minimal.gltf)
add_test(NAME 06_shadows.sweep_unknown_option COMMAND ${EXPECT} 2 "unknown option '--fast'" -- $<TARGET_FILE:06_shadows_sweep> --fast)
# The error view: PCF's visibility against the soft truth on the overview, printed; its mean
# error over every sunlit pixel is below 0.05 (a smoke bound on the printout: the GL tests
# judge PCF over the penumbra).
lightpass_program_test(06_shadows.error_view_reports_pcf_near_the_soft_truth 0
  "against the soft truth: mean \\|error\\| 0\\.0[0-4][0-9]*, p99"
  ${P06} --headless --size 320x180 --mode pcf --show error --out ${CMAKE_BINARY_DIR}/out/06_error.png)
# The chapter's exercises (main.cpp's list; the book's "Exercises"): solutions pass, stubs fail,
# and a plausible wrong answer to each (tests/exercises/wrong/06_shadows/) fails. Exercise 4's
# answer is a number.
# --show visibility and --show cascades carry their keys (issue 29): in the bottom-left corner, on a
# box of grey 24, a swatch per colour show_visibility.frag writes, through the sRGB target (6x6 px
# at this size), beside the text saying what it means (white strokes on 10-60 % of its rows; the
# cascades' short lines 5-60 %), and the box's top row above them. Visibility: 1 -> white 255, 0.5 -> 188, 0 -> black, the sky's
# blue (0.1, 0.15, 0.4) -> (89, 108, 170), mean 122.3. Cascades (four): the tints at full light,
# (1, 0.3, 0.3) -> (255, 149, 149), mean 184.3; (0.3, 1, 0.3) the same mean, green; (0.35, 0.45, 1)
# -> (160, 179, 255), 198; (1, 0.9, 0.2) -> (255, 243, 124), 207.3; then grey 0.5 -> 188.
lightpass_image_test(06_shadows.visibility_has_its_key "wrote" ${CMAKE_BINARY_DIR}/out/06_visibility.png
  --background 24,24,24 --region 2 143 6 6 --mean 255 255 --region 2 152 6 6 --mean 188 188
  --region 2 161 6 6 --mean 0 0 --region 2 170 6 6 --mean 122 123 --region 0 140 180 2 --mean 24 24
  --region 11 143 180 33 --lit 0.1 0.6
  RUN ${P06} --headless --size 320x180 --view corner --mode pcf --show visibility --out ${CMAKE_BINARY_DIR}/out/06_visibility.png)
lightpass_image_test(06_shadows.cascades_have_their_key "wrote" ${CMAKE_BINARY_DIR}/out/06_cascades_key.png
  --background 24,24,24 --region 2 116 6 6 --mean 184 185 --region 2 125 6 6 --mean 184 185
  --region 2 134 6 6 --mean 198 198 --region 2 143 6 6 --mean 207 208 --region 2 152 6 6 --mean 188 188
  --region 0 113 180 2 --mean 24 24 --region 11 116 180 60 --lit 0.05 0.6
  RUN ${P06} --headless --size 320x180 --mode pcf --cascades 4 --show cascades --out ${CMAKE_BINARY_DIR}/out/06_cascades_key.png)
lightpass_exercise_tests(06_shadows 4 NUMBERS 4 WRONG 1 2 3 4)
