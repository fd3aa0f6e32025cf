# Any glTF a reader brings (issue 10): real-model cases and hostile inputs, through the chapter
# programs. Inputs are tests/data/ (tools/scenegen writes them; README.md there lists them).
# Bad input must give its message and exit code within a few seconds: TIMEOUT 10 for inputs
# refused before rendering (an EGL context is made first: ~1 s on llvmpipe), 30 where a
# 160x90 image is rendered.
set(PS01 $<TARGET_FILE:01_forward>)
set(SCENE_OUT ${CMAKE_BINARY_DIR}/out/scene_input)
file(MAKE_DIRECTORY ${SCENE_OUT})

add_executable(png_coverage png_coverage.cpp)
target_link_libraries(png_coverage PRIVATE lightpass_common)

function(scene_test name code regex)
  lightpass_program_test(common.scene.${name} ${code} ${regex} ${ARGN})
  set_tests_properties(common.scene.${name} PROPERTIES TIMEOUT 10)
endfunction()
function(scene_render_test name code regex)
  lightpass_program_test(common.scene.${name} ${code} ${regex} ${ARGN})
  set_tests_properties(common.scene.${name} PROPERTIES TIMEOUT 30)
endfunction()

# A model with neither camera nor lights renders framed and lit: the box covers between 5 %
# and 60 % of the image (the automatic view fits its bounding sphere to the height; a box
# fills less than its sphere) and its pixels are far from black (mean brightest channel >= 60
# of 255, where the default rig's key light alone gives the lit faces > 100).
scene_render_test(auto_view_default_rig_framed_and_lit 0 "within bounds"
  sh -c "'${PS01}' --headless --size 160x90 --scene tests/data/no_camera_no_lights.gltf --out '${SCENE_OUT}/auto.png' && '$<TARGET_FILE:png_coverage>' '${SCENE_OUT}/auto.png' --covered 0.05 0.6 --lit 60")
scene_render_test(auto_view_says_so 0 "no camera: rendering view 'auto'"
  ${PS01} --headless --size 64x36 --scene tests/data/no_camera_no_lights.gltf --out ${SCENE_OUT}/auto_small.png)
scene_render_test(default_rig_says_so 0 "has no lights: using a default rig"
  ${PS01} --headless --size 64x36 --scene tests/data/no_camera_no_lights.gltf --out ${SCENE_OUT}/auto_small2.png)
scene_test(list_puts_auto_after_named_views 0 "views: view auto" ${PS01} --list --scene tests/data/minimal.gltf)
# Strips and fans are drawn: two 1 m quads seen from 3 m above with yfov 0.8 at 16:9, where
# the view spans 2.54 x 4.51 m: 2 / 11.4 = 17.5 % of the image (one quad alone: 8.8 %).
scene_render_test(strip_and_fan_are_drawn 0 "within bounds"
  sh -c "'${PS01}' --headless --size 160x90 --scene tests/data/strip_fan.gltf --out '${SCENE_OUT}/strip_fan.png' && '$<TARGET_FILE:png_coverage>' '${SCENE_OUT}/strip_fan.png' --covered 0.15 0.20")
scene_test(points_only_is_an_error 1 "no triangles to draw" ${PS01} --headless --scene tests/data/points_only.gltf)
scene_render_test(lines_are_skipped_with_a_warning 0 "warning: .*lines .skipped."
  ${PS01} --headless --size 64x36 --scene tests/data/lines_and_triangles.gltf --out ${SCENE_OUT}/lines.png)
scene_test(required_draco_is_refused 1 "requires the extension KHR_draco_mesh_compression" ${PS01} --headless --scene tests/data/requires_draco.gltf)
scene_test(required_meshopt_is_refused 1 "requires the extension EXT_meshopt_compression" ${PS01} --headless --scene tests/data/requires_meshopt.gltf)
scene_render_test(used_extension_warns 0 "warning: .*extension KHR_materials_clearcoat"
  ${PS01} --headless --size 64x36 --scene tests/data/uses_clearcoat.gltf --out ${SCENE_OUT}/clearcoat.png)
scene_render_test(glb_told_by_content 0 "wrote .*glb.png"
  ${PS01} --headless --size 64x36 --scene tests/data/glb_content.gltf --out ${SCENE_OUT}/glb.png)

# The emissive texture's left half is white, its right half black: half of the plane emits
# (saturated, >= 250 in a channel: emissive (2, 1, 0.5)), half does not. Without the texture
# all of it would. Forward (01) and the G-buffer's palette code (02) alike; the bound 0.3..0.7
# leaves room for the plane's lit rim and the texture's filtered seam.
foreach(p 01_forward 02_gbuffer)
  scene_render_test(emissive_texture_emits_where_white_${p} 0 "within bounds"
    sh -c "'$<TARGET_FILE:${p}>' --headless --size 160x90 --scene tests/data/emissive_texture.gltf --out '${SCENE_OUT}/emissive_${p}.png' && '$<TARGET_FILE:png_coverage>' '${SCENE_OUT}/emissive_${p}.png' --bright-share 0.3 0.7")
endforeach()

# Degenerate cameras: an error naming the camera.
foreach(c "yfov_zero|yfov 0 is not between 0 and pi" "yfov_pi|yfov 3.14159 is not between 0 and pi"
          "znear_zero|znear 0 must be > 0" "zfar_below_znear|zfar 0.01 must be greater than znear"
          "zero_scale|camera 'view': its node's transform has a zero" "zero_quaternion|node 'view': its rotation is not a unit quaternion")
  string(REPLACE "|" ";" parts "${c}")
  list(GET parts 0 file)
  list(GET parts 1 message)
  scene_test(camera_${file} 1 "${message}" ${PS01} --headless --scene tests/data/camera_${file}.gltf)
endforeach()

# Bad lights: one rule for every chapter (the loader's): warned by name, left out, exit 0.
foreach(p 01_forward 02_gbuffer 03_light_volumes 04_neon 05_hdr)
  add_test(NAME common.scene.invalid_lights_left_out_${p}
    COMMAND ${EXPECT} 0 "light 'negative_intensity' is left out" "light 'negative_colour' is left out"
            "light 'infinite_intensity' is left out" "light 'negative_range' is left out" --
            $<TARGET_FILE:${p}> --headless --size 64x36 --scene tests/data/lights_invalid.gltf --out ${SCENE_OUT}/lights_${p}.png)
  set_tests_properties(common.scene.invalid_lights_left_out_${p} PROPERTIES TIMEOUT 30)
endforeach()

# Hostile files.
scene_test(accessor_offset_overflow 1 "accessor 0 .4 elements of 12 bytes, stride 12, offset 18446744073709551600. reads past the end"
  ${PS01} --headless --scene tests/data/accessor_offset_overflow.gltf)
scene_test(accessor_count_overflow 1 "accessor 0 .4611686018427387904 elements of 12 bytes.* reads past the end"
  ${PS01} --headless --scene tests/data/accessor_count_overflow.gltf)
scene_test(huge_index_count 1 "indices: accessor 4 .4000000000 elements" ${PS01} --headless --scene tests/data/huge_index_count.gltf)
scene_test(node_dag_is_bounded 1 "more than 1000000 mesh instances" ${PS01} --headless --scene tests/data/node_dag.gltf)
scene_test(node_dag_without_meshes_is_bounded 1 "expands to more than 4000000 nodes" ${PS01} --headless --scene tests/data/node_dag_no_mesh.gltf)
scene_test(node_dag_of_lights_is_bounded 1 "more than 100000 lights" ${PS01} --headless --scene tests/data/node_dag_light.gltf)
scene_render_test(sixteen_bit_png_is_converted 0 "16-bit images read as 8 bits per channel: 'rgb16.png'"
  ${PS01} --headless --size 64x36 --scene tests/data/texture_16bit.gltf --out ${SCENE_OUT}/rgb16.png)
# llvmpipe's GL_MAX_TEXTURE_SIZE is 16384 (CI renders with it; a GPU allowing 32768 would take the image).
scene_render_test(texture_past_the_gl_limit_falls_back 0 "texture 'wide_20000x1.png' is 20000x1, larger than this GL allows"
  env LIBGL_ALWAYS_SOFTWARE=1 LIGHTPASS_SOFTWARE=1 ${PS01} --headless --size 64x36 --scene tests/data/texture_20000x1.gltf --out ${SCENE_OUT}/wide20000.png)
scene_render_test(texture_past_the_loader_limit_falls_back 0 "texture 'wide_40000x1.png' could not be loaded .it is 40000x1, more than the loader accepts"
  ${PS01} --headless --size 64x36 --scene tests/data/texture_40000x1.gltf --out ${SCENE_OUT}/wide40000.png)
scene_render_test(texture_uri_directory 0 "cannot read '.*tests/data/.': it is a directory"
  ${PS01} --headless --size 64x36 --scene tests/data/texture_uri_directory.gltf --out ${SCENE_OUT}/uri_dir.png)
scene_test(buffer_uri_directory 1 "cannot read '.*tests/data/.': it is a directory" ${PS01} --headless --scene tests/data/buffer_uri_directory.gltf)
scene_test(buffer_dev_null 1 "cannot read '.*dev/null': not a regular file" ${PS01} --headless --scene tests/data/buffer_dev_null.gltf)
scene_test(scene_is_a_directory 1 "cannot read scene '.*tests/data': it is a directory" ${PS01} --headless --scene tests/data)
scene_test(scene_is_dev_null 1 "cannot read scene '/dev/null': not a regular file" ${PS01} --headless --scene /dev/null)

# Paths: a relative --scene is found from the current directory first. Here the current
# directory holds its own tests/data/minimal.gltf, a copy of no_camera.gltf: the note about
# the missing camera shows that this one, not the source tree's, was loaded.
set(CWD_ROOT ${CMAKE_BINARY_DIR}/scene_cwd)
configure_file(${CMAKE_CURRENT_SOURCE_DIR}/data/no_camera.gltf ${CWD_ROOT}/tests/data/minimal.gltf COPYONLY)
configure_file(${CMAKE_CURRENT_SOURCE_DIR}/data/no_camera.bin ${CWD_ROOT}/tests/data/no_camera.bin COPYONLY)
add_test(NAME common.scene.relative_scene_from_the_current_directory
  COMMAND ${EXPECT} 0 "minimal.gltf has no camera" -- ${PS01} --headless --size 64x36 --scene tests/data/minimal.gltf --out ${SCENE_OUT}/cwd.png)
set_tests_properties(common.scene.relative_scene_from_the_current_directory PROPERTIES TIMEOUT 30 WORKING_DIRECTORY ${CWD_ROOT})
# ... and from the source root when the current directory has no such file.
add_test(NAME common.scene.relative_scene_from_the_source_root
  COMMAND ${EXPECT} 0 "wrote" --no-match "has no camera" -- ${PS01} --headless --size 64x36 --scene tests/data/minimal.gltf --out ${SCENE_OUT}/root.png)
set_tests_properties(common.scene.relative_scene_from_the_source_root PROPERTIES TIMEOUT 30 WORKING_DIRECTORY ${CMAKE_BINARY_DIR})
# --out: a missing folder is made, and said; only PNG is written.
scene_render_test(out_into_a_missing_directory 0 "created the directory '.*out_new/sub' for --out"
  sh -c "rm -rf '${SCENE_OUT}/out_new' && '${PS01}' --headless --size 64x36 --out '${SCENE_OUT}/out_new/sub/x.png' && test -f '${SCENE_OUT}/out_new/sub/x.png'")
scene_test(out_jpg_is_refused 2 "--out x.jpg: only PNG images are written" ${PS01} --headless --out x.jpg)
scene_test(out_upper_case_png_is_accepted_by_parse 2 "--size 0x0 has no pixels" ${PS01} --headless --out X.PNG --size 0x0)

# Neon extras with numbers no tube can have (chapter 04 reads them): an error naming the node.
file(READ ${CMAKE_CURRENT_SOURCE_DIR}/data/minimal.gltf neon_base)
configure_file(${CMAKE_CURRENT_SOURCE_DIR}/data/minimal.bin ${CMAKE_BINARY_DIR}/neon_extras/minimal.bin COPYONLY)
string(JSON neon_count LENGTH "${neon_base}" nodes)
string(JSON neon_base SET "${neon_base}" scenes 0 nodes ${neon_count} "${neon_count}")
foreach(c "huge_length|\"length\": 1e30, \"intensity\": 1|\"length\" must be" "negative_colour|\"length\": 1, \"intensity\": 1, \"color\": [1, -1, 1]|\"color\" must be"
          "huge_intensity|\"length\": 1, \"intensity\": 1e39|\"intensity\" must be")
  string(REPLACE "|" ";" parts "${c}")
  list(GET parts 0 name)
  list(GET parts 1 body)
  list(GET parts 2 message)
  string(JSON neon_doc SET "${neon_base}" nodes ${neon_count} "{\"name\": \"sign_${name}\", \"extras\": {\"lightpass\": {\"neon\": {${body}}}}}")
  file(WRITE ${CMAKE_BINARY_DIR}/neon_extras/neon_${name}.gltf "${neon_doc}")
  add_test(NAME common.scene.neon_${name}_names_the_node
    COMMAND ${EXPECT} 1 "neon light 'sign_${name}': ${message}" -- $<TARGET_FILE:04_neon> --headless --size 64x36 --scene ${CMAKE_BINARY_DIR}/neon_extras/neon_${name}.gltf)
  set_tests_properties(common.scene.neon_${name}_names_the_node PROPERTIES TIMEOUT 10)
endforeach()

# Any scene a reader brings, to the end (issue 30): each file of tests/data/ (README.md there)
# with the message it must print and its exit code.
# Compressed meshes as their writers make them: named before tinygltf fails on their accessors.
scene_test(draco_compressed_is_named 1 "requires the extension KHR_draco_mesh_compression, which lightpass does not support .a compressed mesh"
  ${PS01} --headless --scene tests/data/draco_compressed.gltf)
scene_test(meshopt_compressed_is_named 1 "requires the extension EXT_meshopt_compression, which lightpass does not support .a compressed mesh"
  ${PS01} --headless --scene tests/data/meshopt_compressed.glb)
# Nothing to draw: an error, never a blank image.
foreach(f indices_count_zero no_vertices strip_two_indices)
  scene_test(nothing_to_draw_${f} 1 "${f}.gltf: the scene has no triangles to draw" ${PS01} --headless --scene tests/data/${f}.gltf)
endforeach()
foreach(f position_all_zero degenerate_triangles)
  scene_test(nothing_to_draw_${f} 1 "${f}.gltf: the scene has no triangles to draw .its 2 triangles all have zero area"
    ${PS01} --headless --scene tests/data/${f}.gltf)
endforeach()
scene_test(position_vec2_is_refused 1 "mesh 'plane' primitive 0: POSITION .accessor 0. is VEC2. glTF requires VEC3"
  ${PS01} --headless --scene tests/data/position_vec2.gltf)
scene_test(position_scalar_is_refused 1 "mesh 'plane' primitive 0: POSITION .accessor 0. is SCALAR. glTF requires VEC3"
  ${PS01} --headless --scene tests/data/position_scalar.gltf)
# Accessors without a bufferView are zeros: the plane is drawn (minimal.gltf's covers 7.5 % of
# the image), beside a second primitive whose indices are all 0 (no area, nothing drawn).
foreach(f attribute_no_buffer_view indices_no_buffer_view)
  scene_render_test(${f}_is_zeros 0 "within bounds"
    sh -c "'${PS01}' --headless --size 160x90 --scene tests/data/${f}.gltf --out '${SCENE_OUT}/${f}.png' && '$<TARGET_FILE:png_coverage>' '${SCENE_OUT}/${f}.png' --covered 0.07 0.08")
endforeach()
# One image file named by 16 images renders without a word (decoded once; the budget test is
# Scene.ImagesOfTheSameBytesAreCountedOnce).
add_test(NAME common.scene.image_shared_16_loads_without_a_warning
  COMMAND ${EXPECT} 0 "wrote" --no-match "warning|could not be loaded" -- ${PS01} --headless --size 64x36 --scene tests/data/image_shared_16.gltf --out ${SCENE_OUT}/shared16.png)
set_tests_properties(common.scene.image_shared_16_loads_without_a_warning PROPERTIES TIMEOUT 30)
# Cameras: a yfov that is pi as a float is refused; legal ones that leave no image are made usable, and said.
scene_test(camera_yfov_float_pi 1 "camera 'view': yfov 3.14159265 is below pi, but rounds to pi as a float"
  ${PS01} --headless --scene tests/data/camera_yfov_float_pi.gltf)
scene_render_test(camera_yfov_3_14159_is_narrowed 0 "yfov 3.14159 leaves the scene a speck in the middle of the image. using 2.8"
  sh -c "'${PS01}' --headless --size 160x90 --scene tests/data/camera_yfov_3_14159.gltf --out '${SCENE_OUT}/yfov.png' 2>&1 && '$<TARGET_FILE:png_coverage>' '${SCENE_OUT}/yfov.png' --covered 0.0003 0.01")
scene_render_test(camera_znear_tiny_is_raised 0 "znear 1e-30 beside zfar 50 leaves the depth buffer no precision.*using znear"
  sh -c "'${PS01}' --headless --size 160x90 --scene tests/data/camera_znear_tiny.gltf --out '${SCENE_OUT}/znear.png' 2>&1 && '$<TARGET_FILE:png_coverage>' '${SCENE_OUT}/znear.png' --covered 0.07 0.08")
# The automatic view of extreme sizes and places: the plane alone framed as offset_0.gltf's (at
# the origin, 1 m across) frames it, the same image far away, the far ones moved and said.
add_test(NAME common.scene.auto_view_control_offset_0
  COMMAND ${PS01} --headless --size 160x90 --scene tests/data/offset_0.gltf --out ${SCENE_OUT}/offset_0.png)
set_tests_properties(common.scene.auto_view_control_offset_0 PROPERTIES TIMEOUT 30 FIXTURES_SETUP scene_offset_0)
foreach(c "extent_1e19|is 2.82843e.19 m across, where float lighting overflows: drawn scaled by 2.-64"
          "extent_1e-19|is 2.82843e-19 m across, where float lighting underflows: drawn scaled by 2.63" "offset_1e6|lies 1e.06 m from the origin.*moved by .-1e.06, -0, -0."
          "offset_5e6|lies 5e.06 m from the origin" "offset_1e7|lies 1e.07 m from the origin")
  string(REPLACE "|" ";" parts "${c}")
  list(GET parts 0 file)
  list(GET parts 1 message)
  add_test(NAME common.scene.auto_view_${file}
    COMMAND ${EXPECT} 0 "${message}" -- ${PS01} --headless --size 160x90 --scene tests/data/${file}.gltf --out ${SCENE_OUT}/${file}.png
            --and $<TARGET_FILE:image_stats> ${SCENE_OUT}/${file}.png --matches ${SCENE_OUT}/offset_0.png)
  set_tests_properties(common.scene.auto_view_${file} PROPERTIES TIMEOUT 30 FIXTURES_REQUIRED scene_offset_0)
endforeach()
# Chapter 10's whole frame (its speckles were worst at 1e6 m): the same image as at the origin.
add_test(NAME common.scene.auto_view_control_offset_0_10_frame
  COMMAND $<TARGET_FILE:10_frame> --headless --size 160x90 --scene tests/data/offset_0.gltf --out ${SCENE_OUT}/offset_0_10.png)
set_tests_properties(common.scene.auto_view_control_offset_0_10_frame PROPERTIES TIMEOUT 30 FIXTURES_SETUP scene_offset_0_10)
add_test(NAME common.scene.auto_view_offset_1e6_10_frame
  COMMAND ${EXPECT} 0 "lies 1e.06 m from the origin" -- $<TARGET_FILE:10_frame> --headless --size 160x90 --scene tests/data/offset_1e6.gltf
          --out ${SCENE_OUT}/offset_1e6_10.png --and $<TARGET_FILE:image_stats> ${SCENE_OUT}/offset_1e6_10.png --matches ${SCENE_OUT}/offset_0_10.png)
set_tests_properties(common.scene.auto_view_offset_1e6_10_frame PROPERTIES TIMEOUT 30 FIXTURES_REQUIRED scene_offset_0_10)
# Every face turned away from the automatic view: it looks from the side that sees them.
scene_render_test(auto_view_sees_front_faces 0 "every face of back_faces_only.gltf faces away from the automatic view's usual side"
  sh -c "'${PS01}' --headless --size 160x90 --scene tests/data/back_faces_only.gltf --out '${SCENE_OUT}/back.png' && '$<TARGET_FILE:png_coverage>' '${SCENE_OUT}/back.png' --covered 0.07 0.08 --lit 40")
# Lights that light nothing: left out by name; when none is left, the default rig, said.
scene_render_test(light_range_tiny_is_left_out 0 "light 'light' is left out: its range 1e-30 m is a millionth of the scene's size"
  ${PS01} --headless --size 64x36 --scene tests/data/light_range_tiny.gltf --out ${SCENE_OUT}/range.png)
scene_render_test(only_light_left_out_gets_the_rig 0 "none of the scene's 1 lights can be used .each is named above.: using a default rig"
  sh -c "'${PS01}' --headless --size 160x90 --scene tests/data/only_light_left_out.gltf --out '${SCENE_OUT}/rig.png' 2>&1 && '$<TARGET_FILE:png_coverage>' '${SCENE_OUT}/rig.png' --covered 0.07 0.08 --lit 60")
# Material factors past 1: clamped with the material named, in the chapters whose light cut-off they broke.
foreach(p 01_forward 03_light_volumes 05_hdr 10_frame)
  scene_render_test(material_huge_base_color_${p} 0 "material 'grey': baseColorFactor .3e.38, 3e.38, 3e.38, 1. reflects more than all the light: clamped to 1"
    $<TARGET_FILE:${p}> --headless --size 64x36 --scene tests/data/material_huge_base_color.gltf --out ${SCENE_OUT}/base_${p}.png)
  scene_render_test(material_huge_specular_${p} 0 "material 'grey': the specular colour .* reflects more than all the light: clamped to 1"
    $<TARGET_FILE:${p}> --headless --size 64x36 --scene tests/data/material_huge_specular.gltf --out ${SCENE_OUT}/spec_${p}.png)
endforeach()
# 100 000 unbounded lights from a 4 KB file: refused up front, naming the bound.
scene_test(lights_100000_are_bounded 1 "its 100000 lights reach 1e.05 times the whole scene.*more work a frame than the loader accepts .4096."
  $<TARGET_FILE:03_light_volumes> --headless --scene tests/data/lights_100000.gltf)
# Messages: what and where, in words.
scene_test(buffer_dev_zero 1 "cannot read '/dev/zero': not a regular file" ${PS01} --headless --scene tests/data/buffer_dev_zero.gltf)
scene_render_test(image_huge_header 0 "texture 'huge_header.png' could not be loaded .it is 100000x100000, more than the loader accepts"
  ${PS01} --headless --size 64x36 --scene tests/data/image_huge_header.gltf --out ${SCENE_OUT}/huge_header.png)
scene_test(glb_parse_error_shows_bytes_as_hex 1 "cannot load scene '.*glb_bad_json.glb': .*[\\\\]x9B" ${PS01} --headless --scene tests/data/glb_bad_json.glb)
set(LOOP_DIR ${CMAKE_BINARY_DIR}/scene_loop)
file(MAKE_DIRECTORY ${LOOP_DIR})
file(CREATE_LINK loop_b.gltf ${LOOP_DIR}/loop_a.gltf SYMBOLIC)
file(CREATE_LINK loop_a.gltf ${LOOP_DIR}/loop_b.gltf SYMBOLIC)
scene_test(symlink_loop 1 "cannot read scene '.*loop_a.gltf': Too many levels of symbolic links" ${PS01} --headless --scene ${LOOP_DIR}/loop_a.gltf)
scene_test(out_empty_is_refused 2 "--out needs a file name, not ''" sh -c "'${PS01}' --headless --out ''")
scene_test(scene_empty_is_refused 2 "--scene needs a file name, not ''" sh -c "'${PS01}' --headless --scene ''")
