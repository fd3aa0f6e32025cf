# Chapter 04: the neon light. Unit tests of the maths and the capsule (no OpenGL), GPU tests
# (the GLSL against the C++, the renderer against the ground truth), and the program itself:
# reference images per mode, outputs and bad input.
lightpass_gtests(04_neon unit lightpass_04_neon
  unit/test_04_neon_math.cpp
  unit/test_04_capsule.cpp
  unit/test_04_scene.cpp
)
# The GLSL against the C++ (test_04_neon_gl), and the deferred path (capsule volumes through
# chapter 03's stencil) against the forward pass (test_04_neon_volumes_gl).
lightpass_gtests(04_neon gl lightpass_04_neon
  unit/test_04_neon_gl.cpp
  unit/test_04_neon_volumes_gl.cpp
  unit/test_04_twins_gl.cpp
  unit/glsl_twin.cpp
)

# The program: reference images per mode (tests/reference/04_neon/, made on llvmpipe), the
# capsule volumes by default and the forward pass (--forward 1); the night street's signs.
set(P04 $<TARGET_FILE:04_neon>)
foreach(mode improved ground-truth source points representative-point analytic-diffuse)
  lightpass_program_test(04_neon.reference.${mode} 0 "references match" ${P04} --check --mode ${mode} --out ${CHECK_OUT}/04_neon)
endforeach()
lightpass_program_test(04_neon.reference.street_neon 0 "6 of 6 references match"
  ${P04} --check --scene assets/street_neon/street_neon.gltf --out ${CHECK_OUT}/04_neon_street)
lightpass_program_test(04_neon.headless_says_what_the_capsules_shaded 0
  "capsule volumes: frame took .* ms.*neon fragments shaded [0-9]+, lit [0-9]+, overshading"
  ${P04} --headless --size 160x90 --out ${CMAKE_BINARY_DIR}/out/04_headless.png)
lightpass_program_test(04_neon.headless_forward_writes_png 0 "forward: frame took"
  ${P04} --headless --size 160x90 --forward 1 --out ${CMAKE_BINARY_DIR}/out/04_headless_forward.png)
lightpass_program_test(04_neon.bench_prints_json 0 "\"name\":\"neon: capsule volumes, stencil\""
  ${P04} --bench --frames 2 --size 160x90 --count 0)
lightpass_program_test(04_neon.bad_mode 2 "unknown mode 'laser'" ${P04} --mode laser)
lightpass_program_test(04_neon.bad_knob 2 "--samples must be between" ${P04} --samples 0)
# --show waste carries its key (issue 29): in the bottom-left corner, on a box of grey 24, a swatch
# per colour neon_volume.frag's SHOW_WASTE writes, through the sRGB target (6x6 px at this size):
# green 0.2 -> (0, 124, 0), mean 41.3 steps; red 0.7 -> (218, 0, 0), 72.7; blue (0, 0.1, 0.7) ->
# (0, 89, 218), 102.3; beside them the text saying what each means, whose white strokes light
# 10-60 % of its rows, and the box's top row above them.
lightpass_image_test(04_neon.waste_has_its_key "wrote" ${CMAKE_BINARY_DIR}/out/04_waste.png
  --background 24,24,24 --region 2 143 6 6 --mean 41 42 --lit 1 1 --region 2 152 6 6 --mean 72 73
  --region 2 161 6 6 --mean 102 103 --region 0 140 200 2 --mean 24 24 --region 11 143 200 33 --lit 0.1 0.6
  RUN ${P04} --headless --size 320x180 --show waste --out ${CMAKE_BINARY_DIR}/out/04_waste.png)
# Any scene loads; one without neon lights is lit by its ordinary lights alone: chapter 01's
# scene renders as chapter 01 renders it (its per-pixel reference; the deferred path's G-buffer
# rounding leaves 3 pixels beyond 3 steps on llvmpipe, --check allows 57).
lightpass_image_test(04_neon.scene_without_neon_renders_as_chapter_01 "0 neon tubes" ${CMAKE_BINARY_DIR}/out/04_forward_scene.png
  --matches ${CMAKE_SOURCE_DIR}/tests/reference/01_forward/overview_per-pixel.png
  RUN ${P04} --headless --size 320x180 --scene assets/forward/forward.gltf --out ${CMAKE_BINARY_DIR}/out/04_forward_scene.png)

# A user's scene with a neon node, and one whose description is broken: tests/data's
# minimal.gltf with a node added (written at configure time, beside a copy of its buffer).
file(READ ${CMAKE_CURRENT_SOURCE_DIR}/data/minimal.gltf neon_gltf)
configure_file(${CMAKE_CURRENT_SOURCE_DIR}/data/minimal.bin ${CMAKE_BINARY_DIR}/neon_data/minimal.bin COPYONLY)
string(JSON neon_nodes LENGTH "${neon_gltf}" nodes)
string(JSON neon_gltf SET "${neon_gltf}" scenes 0 nodes ${neon_nodes} "${neon_nodes}")
set(neon_good "${neon_gltf}")
string(JSON neon_good SET "${neon_good}" nodes ${neon_nodes}
  "{\"name\": \"sign\", \"translation\": [0, 0.5, 0], \"extras\": {\"lightpass\": {\"neon\": {\"length\": 1.5, \"intensity\": 0.5, \"color\": [1, 0.3, 0.6]}}}}")
file(WRITE ${CMAKE_BINARY_DIR}/neon_data/neon_minimal.gltf "${neon_good}")
string(JSON neon_bad SET "${neon_gltf}" nodes ${neon_nodes}
  "{\"name\": \"broken_sign\", \"extras\": {\"lightpass\": {\"neon\": {\"length\": -2, \"intensity\": 1}}}}")
file(WRITE ${CMAKE_BINARY_DIR}/neon_data/neon_bad_length.gltf "${neon_bad}")
# The sign lights the user's scene: minimal.gltf's mean is 50.1 steps without it and 53.5 with
# it (llvmpipe; the pink glow on the plane below). A sign that adds nothing stays under 51.5.
lightpass_image_test(04_neon.user_scene_with_neon "1 neon tubes.*neon fragments shaded [1-9]" ${CMAKE_BINARY_DIR}/out/04_minimal.png
  --background ${BACKGROUND_SRGB8} --mean 51.5 56 --lit 0.05 0.12
  RUN ${P04} --headless --size 160x90 --scene ${CMAKE_BINARY_DIR}/neon_data/neon_minimal.gltf --out ${CMAKE_BINARY_DIR}/out/04_minimal.png)
lightpass_program_test(04_neon.malformed_neon 1 "neon light 'broken_sign': \"length\" must be >= 0"
  ${P04} --headless --size 160x90 --scene ${CMAKE_BINARY_DIR}/neon_data/neon_bad_length.gltf)
# The sweep's options.
add_test(NAME 04_neon.sweep_unknown_option COMMAND ${EXPECT} 2 "unknown option '--fast'" -- $<TARGET_FILE:04_neon_sweep> --fast)

# The chapter's exercises (main.cpp's list; the book's "Exercises"): solutions pass, stubs fail.
lightpass_exercise_tests(04_neon 3)
