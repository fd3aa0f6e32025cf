# Chapter 02: the G-buffer's maths on the CPU, the G-buffer on a headless context, and the
# program itself (reference images of the lit result and of every buffer, outputs, bad input).
add_executable(gbuffer_tests unit/test_02_encoding.cpp)
target_link_libraries(gbuffer_tests PRIVATE lightpass_02_gbuffer GTest::gtest_main)
gtest_discover_tests(gbuffer_tests TEST_PREFIX 02_gbuffer.unit. DISCOVERY_TIMEOUT 60)

add_executable(gbuffer_gl_tests unit/test_02_gbuffer_gl.cpp)
target_link_libraries(gbuffer_gl_tests PRIVATE lightpass_02_gbuffer GTest::gtest_main)
gtest_discover_tests(gbuffer_gl_tests TEST_PREFIX 02_gbuffer.gl. DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 300)

# The program: reference images of the lit result and of every buffer, outputs, bad input.
set(P02 $<TARGET_FILE:02_gbuffer>)
foreach(mode deferred layout-source ambient-directional albedo normal depth specular exponent emissive position)
  lightpass_program_test(02_gbuffer.reference.${mode} 0 "references match" ${P02} --check --mode ${mode} --out ${CHECK_OUT}/02_gbuffer)
endforeach()
lightpass_program_test(02_gbuffer.headless_writes_png 0 "wrote .*02_headless.png"
  ${P02} --headless --size 160x90 --out ${CMAKE_BINARY_DIR}/out/02_headless.png)
lightpass_program_test(02_gbuffer.prints_bytes_per_pixel 0 "G-buffer layout 'ours': 16 bytes per pixel"
  ${P02} --headless --size 64x36 --out ${CMAKE_BINARY_DIR}/out/02_bytes.png)
lightpass_program_test(02_gbuffer.source_layout_bytes 0 "G-buffer layout 'source': 20 bytes per pixel"
  ${P02} --headless --size 64x36 --mode layout-source --out ${CMAKE_BINARY_DIR}/out/02_source.png)
lightpass_program_test(02_gbuffer.bench_prints_both_passes 0 "\"name\":\"geometry: fill the G-buffer\".*\"name\":\"lighting: full-screen pass\""
  ${P02} --bench --frames 2 --size 160x90)
lightpass_program_test(02_gbuffer.every_layout_renders 0 "wrote"
  ${P02} --headless --size 64x36 --layout 8 --out ${CMAKE_BINARY_DIR}/out/02_reversed.png)
lightpass_program_test(02_gbuffer.bad_layout 2 "--layout must be between 0 and 8" ${P02} --layout 9)
lightpass_program_test(02_gbuffer.bad_mode 2 "unknown mode 'gbuffer'" ${P02} --mode gbuffer)
lightpass_program_test(02_gbuffer.street_with_emissive 0 "wrote"
  ${P02} --headless --size 160x90 --scene assets/street/street.gltf --view street_level --mode emissive --out ${CMAKE_BINARY_DIR}/out/02_street_emissive.png)
lightpass_program_test(02_gbuffer.mesh_without_normals 0 "wrote"
  ${P02} --headless --size 160x90 --scene tests/data/nonindexed_nonormals.gltf --out ${CMAKE_BINARY_DIR}/out/02_nonindexed.png)

# The window path (GLFW + the panel) under a virtual X display, closing itself after 3 frames.
lightpass_program_test(02_gbuffer.window_screenshot 0 "window screenshot, 320x180"
  xvfb-run -a -s "-screen 0 320x180x24" ${P02} --size 320x180 --frames 3 --out ${CMAKE_BINARY_DIR}/out/02_window.png)

# Views that sample the distant textured floor get a 2 % allowance only on a renderer other
# than the one that made the references (texture LOD is implementation-defined); on the
# same renderer, every view is held to 0.1 %.
add_test(NAME 02_gbuffer.reference_same_renderer_is_strict
  COMMAND ${EXPECT} 0 "aisle_deferred .*allowed 0.100%" -- ${P02} --check --view aisle --mode deferred --out ${CHECK_OUT}/02_strict)
add_test(NAME 02_gbuffer.reference_other_renderer_allowance
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/other_renderer.sh ${P02} 02_gbuffer ${CMAKE_SOURCE_DIR} ${CMAKE_BINARY_DIR}/other_renderer_02
  -- "aisle_deferred .*allowed 2.000%\\) \\[other renderer\\]" "aisle_specular .*allowed 0.100%\\)$")

# The sweep measures through common/measure.h and every row of its table names what measured
# it: the renderer, the size and the frames (here 2, as asked; what the means are over).
set(SWEEP02_OUT ${CMAKE_BINARY_DIR}/out/02_sweep)
add_test(NAME 02_gbuffer.sweep_rows_name_renderer_size_and_frames COMMAND ${EXPECT} 0
  "^lights,method,total_ms,geometry_ms,lighting_ms,fragments_shaded,renderer,width,height,frames$"
  "^1,forward,[0-9.e-]+,0,[0-9.e-]+,[1-9][0-9]*,[^,]+.*,32,18,2$"
  "^1,deferred,[0-9.e-]+,[0-9.e-]+,[0-9.e-]+,576,[^,]+.*,32,18,2$"
  -- sh -c "$<TARGET_FILE:02_gbuffer_sweep> --out ${SWEEP02_OUT} --only lights --light-size 32x18 --max-lights 1 --frames 2 >/dev/null && cat ${SWEEP02_OUT}/02_lights.csv")
set_tests_properties(02_gbuffer.sweep_rows_name_renderer_size_and_frames PROPERTIES TIMEOUT 120)
