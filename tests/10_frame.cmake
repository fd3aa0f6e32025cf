# Chapter 10: the whole frame, its transparency and its MSAA: GPU tests of the glass against the
# exact per-pixel order and its hard cases, of MSAA and of the whole frame, and the program
# (references, bad input).
lightpass_gtests(10_frame gl lightpass_10_frame unit/test_10_transparency_gl.cpp
  unit/test_10_twins_gl.cpp unit/glsl_twin.cpp)

# The program: its references (tests/reference/10_frame/, made on llvmpipe and looked at), what
# a headless run says, and bad input.
set(P10 $<TARGET_FILE:10_frame>)
set(GLASS assets/glass/glass.gltf)
# The default: the whole frame on the street with its shop windows, every stage on and each
# stage off in turn; the same in the atrium; and the glass room's transparency (--mode frame).
lightpass_program_test(10_frame.reference.street_shop 0 "9 of 9 references match" ${P10} --check --out ${CHECK_OUT}/10_frame)
lightpass_program_test(10_frame.reference.atrium 0 "5 of 5 references match"
  ${P10} --check --scene assets/atrium/atrium.gltf --out ${CHECK_OUT}/10_frame_atrium)
lightpass_program_test(10_frame.reference.glass 0 "15 of 15 references match" ${P10} --check --scene ${GLASS} --out ${CHECK_OUT}/10_frame_glass)
lightpass_program_test(10_frame.headless_says_what_it_drew 0
  "7 transparent surfaces, wboit: frame took .* ms.*exact order: [1-9][0-9]* fragments"
  ${P10} --headless --mode frame --scene ${GLASS} --size 160x90 --transparency wboit --show error --out ${CMAKE_BINARY_DIR}/out/10_headless.png)
# --show error carries its key, as chapter 02's difference does: the bar ends red under its
# right end (the glass's errors there are black), mean 80-100 steps with every pixel lit.
lightpass_image_test(10_frame.error_map_has_its_key "wboit against the exact order" ${CMAKE_BINARY_DIR}/out/10_error_key.png
  --region 296 162 20 6 --mean 80 100 --lit 1 1
  RUN ${P10} --headless --mode frame --scene ${GLASS} --size 320x180 --transparency wboit --show error
      --out ${CMAKE_BINARY_DIR}/out/10_error_key.png)
lightpass_program_test(10_frame.bench_prints_the_wboit_passes 0 "\"name\":\"transparency: WBOIT composite\""
  ${P10} --bench --mode frame --scene ${GLASS} --frames 2 --size 160x90 --transparency wboit)
lightpass_program_test(10_frame.bad_transparency 2 "transparency" ${P10} --transparency painter)
lightpass_program_test(10_frame.bad_global 2 "global" ${P10} --global vertex)
# --global picks the whole frame's global pass: as a fragment pass it shades one fragment per
# pixel (64 x 36 = 2304), in compute none (the bench's GL_SAMPLES_PASSED of the pass).
lightpass_program_test(10_frame.global_fragment_shades_a_fragment_per_pixel 0
  "\"name\":\"global: ambient \\+ directional \\(chapter 03\\)\",[^}]*\"fragments\":2304,"
  ${P10} --bench --mode whole --size 64x36 --frames 1 --global fragment)
lightpass_program_test(10_frame.global_compute_shades_no_fragment 0
  "\"name\":\"global: ambient \\+ directional \\(chapter 03\\)\",[^}]*\"fragments\":0,"
  ${P10} --bench --mode whole --size 64x36 --frames 1 --global compute)
# A scene without glass is chapter 03's frame, bit for bit up to its reference's tolerance: the
# stage draws nothing (chapter 03's stencil reference of the street).
lightpass_image_test(10_frame.scene_without_glass_renders_as_chapter_03 "0 transparent surfaces" ${CMAKE_BINARY_DIR}/out/10_street.png
  --matches ${CMAKE_SOURCE_DIR}/tests/reference/03_light_volumes/street_level_stencil.png
  RUN ${P10} --headless --mode frame --size 320x180 --scene assets/street/street.gltf --view street_level --out ${CMAKE_BINARY_DIR}/out/10_street.png)
# The sweep's options (the sweep itself runs on the GPU machine through tools/device-measure).
lightpass_program_test(10_frame.sweep_unknown_option 2 "unknown option '--fast'" $<TARGET_FILE:10_frame_sweep> --fast)
lightpass_program_test(10_frame.sweep_bad_layers 2 "--layers must be between 1 and 128" $<TARGET_FILE:10_frame_sweep> --layers 0)

# --mode whole: every stage of the book in one frame (whole_frame.h).
# With every stage this chapter assembles switched off, the frame is chapter 05's HDR street
# (its reference, made by chapter 05's own program: max 0 on llvmpipe).
lightpass_image_test(10_frame.whole_with_every_stage_off_is_chapter_05s_street "not run  shadow map" ${CMAKE_BINARY_DIR}/out/10_whole_off.png
  --matches ${CMAKE_SOURCE_DIR}/tests/reference/05_hdr/street_level_reinhard.png
  RUN ${P10} --headless --mode whole --size 320x180 --scene assets/street/street.gltf --view street_level --shadows 0
      --clustered 0 --ao 0 --indirect 0 --transparency off --bloom off --out ${CMAKE_BINARY_DIR}/out/10_whole_off.png)
# Chapter 09's clusters instead of the volumes: the same image within chapter 09's cross-check (a
# step here and there; chapter 05's reference tolerance).
lightpass_image_test(10_frame.whole_with_clusters_is_chapter_05s_street "runs     local lights: clusters" ${CMAKE_BINARY_DIR}/out/10_whole_clusters.png
  --matches ${CMAKE_SOURCE_DIR}/tests/reference/05_hdr/street_level_reinhard.png
  RUN ${P10} --headless --mode whole --size 320x180 --scene assets/street/street.gltf --view street_level --shadows 0
      --ao 0 --indirect 0 --transparency off --bloom off --out ${CMAKE_BINARY_DIR}/out/10_whole_clusters.png)
# Every stage the neon street needs runs, each timed as its chapter names it (the frame budget):
# the tubes' light in the clusters' shading pass (no neon pass of its own, their glass after the
# composite), or with --tubes volumes chapter 04's capsule volumes; and the CPU's time per frame
# is reported beside the GPU's (a number above zero).
lightpass_program_test(10_frame.whole_bench_times_every_stage 0
  "shadow map: depth from the sun.*local lights: clustered: shade.*ssgi: .*glass: the tubes themselves.*hdr: tonemap.*\"cpu_ms\":[0-9.]*[1-9]"
  ${P10} --bench --frames 1 --mode whole --size 160x90 --scene assets/street_neon/street_neon.gltf)
add_test(NAME 10_frame.whole_tubes_in_the_clusters_have_no_volume_pass COMMAND ${EXPECT} 0 "local lights: clustered: shade"
  --no-match "neon: capsule volumes" -- ${P10} --bench --frames 1 --mode whole --size 160x90 --scene assets/street_neon/street_neon.gltf)
set_tests_properties(10_frame.whole_tubes_in_the_clusters_have_no_volume_pass PROPERTIES TIMEOUT 300)
lightpass_program_test(10_frame.whole_tubes_as_volumes_time_their_pass 0
  "local lights: clustered: shade.*neon: capsule volumes, stencil.*ssgi: "
  ${P10} --bench --frames 1 --mode whole --size 160x90 --scene assets/street_neon/street_neon.gltf --tubes volumes)
# With clusters the glass reads the whole frame's lists (built for every cell when the scene has
# glass): one set a frame, so the glass's own list pass does not run; over the volumes it does.
add_test(NAME 10_frame.whole_glass_reads_the_frames_clusters COMMAND ${EXPECT} 0 "\"name\":\"transparency: sorted, back to front\""
  --no-match "transparency: light lists" -- ${P10} --bench --frames 1 --mode whole --size 160x90)
set_tests_properties(10_frame.whole_glass_reads_the_frames_clusters PROPERTIES TIMEOUT 300)
lightpass_program_test(10_frame.whole_glass_over_the_volumes_builds_its_own_lists 0
  "\"name\":\"transparency: light lists [(]chapter 09, every cluster[)]\""
  ${P10} --bench --frames 1 --mode whole --size 160x90 --clustered 0)
# What a scene does not need is not run, and the program says why (the atrium: no tubes).
lightpass_program_test(10_frame.whole_says_what_it_does_not_run 0
  "not run  neon tubes: in the clusters [(]chapters 04, 09[)] [(]no neon tubes[)]"
  ${P10} --headless --mode whole --size 64x36 --scene assets/atrium/atrium.gltf --out ${CMAKE_BINARY_DIR}/out/10_whole_atrium.png)
# The window path under a virtual X display: a smoke test (the panel covers the left half, so the
# lit fraction says that the window drew; the references check the frame).
lightpass_image_test(10_frame.window_smoke_screenshot "window screenshot, 640x360" ${CMAKE_BINARY_DIR}/out/10_window.png
  --size 640x360 --background ${BACKGROUND_SRGB8} --lit 0.3 1
  RUN xvfb-run -a -s "-screen 0 640x360x24" ${P10} --size 640x360 --frames 3 --out ${CMAKE_BINARY_DIR}/out/10_window.png)
# The panel's scene switch (common/app.h, App::switch_scene), picked by the test hook after the
# second frame: the chapter's body runs again on the atrium, whose whole frame the window shows
# (the panel covers the left half; its right half is the atrium's, not the street's). A scene
# that does not load is reported, and the street kept.
lightpass_image_test(10_frame.window_switches_to_the_atrium "scene: assets/atrium/atrium.gltf [(]view overview[)]"
  ${CMAKE_BINARY_DIR}/out/10_window_atrium.png --size 640x360 --lit 0.3 1
  RUN env LIGHTPASS_TEST_SWITCH_SCENE=assets/atrium/atrium.gltf
      xvfb-run -a -s "-screen 0 640x360x24" ${P10} --size 640x360 --frames 3 --out ${CMAKE_BINARY_DIR}/out/10_window_atrium.png)
lightpass_image_test(10_frame.window_keeps_its_scene_when_the_new_one_fails
  "could not load tests/data/malformed.gltf: .*[(]kept assets/street_shop/street_shop.gltf[)]"
  ${CMAKE_BINARY_DIR}/out/10_window_kept.png --size 320x180 --lit 0.3 1
  RUN env LIGHTPASS_TEST_SWITCH_SCENE=tests/data/malformed.gltf
      xvfb-run -a -s "-screen 0 320x180x24" ${P10} --size 320x180 --frames 3 --out ${CMAKE_BINARY_DIR}/out/10_window_kept.png)
# The stage plan is where stages are switched: one click on the plan's box of the sun's shadow
# map (not the knob's above it; at one frame a second, the cursor gone before the next frame)
# turns the stage off. AO and indirect light are off to keep llvmpipe's frames short.
add_test(NAME 10_frame.window_plan_box_switches_its_stage
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/window_click.sh ${P10} 1280x720 27 560 "^panel: --shadows 0$" --ao 0 --indirect 0)
set_tests_properties(10_frame.window_plan_box_switches_its_stage PROPERTIES TIMEOUT 600)
# MSAA with deferred shading (chapters/10_frame/msaa.h): the cross-checks, the edges of a scene
# known to the pixel, the exact fragment count and the tonemap order at a bright edge.
lightpass_gtests(10_msaa gl lightpass_10_frame unit/test_10_msaa_gl.cpp)
# The whole frame: a size change mid-run, and each stage off and on again.
lightpass_gtests(10_whole gl lightpass_10_frame unit/test_10_whole_gl.cpp unit/test_10_stages_gl.cpp
  unit/test_10_whole_msaa_gl.cpp)
# The program with --msaa 4, an option of the whole frame: with the stages that have no MSAA yet
# off, the street is chapter 05's HDR street except at its edges, where the samples are averaged
# (a mean difference of a few steps over the image, and more than none); with them on, the plan
# says which it leaves out; the glass study refuses it.
lightpass_image_test(10_frame.whole_msaa_4_is_chapter_05s_street_with_resolved_edges "MSAA 4 samples" ${CMAKE_BINARY_DIR}/out/10_msaa.png
  --near ${CMAKE_SOURCE_DIR}/tests/reference/05_hdr/street_level_reinhard.png 4
  --differs-from ${CMAKE_SOURCE_DIR}/tests/reference/05_hdr/street_level_reinhard.png 0.5
  RUN ${P10} --headless --mode whole --size 320x180 --scene assets/street/street.gltf --view street_level --msaa 4
      --shadows 0 --clustered 0 --ao 0 --indirect 0 --transparency off --bloom off --out ${CMAKE_BINARY_DIR}/out/10_msaa.png)
# The sun's map, the tubes (their capsules, per sample on the edges: with MSAA there are no
# clusters to shade them in) and the glass (into the samples before the resolve) run; AO does not.
add_test(NAME 10_frame.whole_msaa_says_what_it_does_not_run COMMAND ${EXPECT} 0
  "runs     shadow map of the sun [(]chapter 06[)]"
  "runs     neon tubes: capsule volumes [(]chapter 04; per sample on edges, chapter 10[)]"
  "runs     glass, into the samples before the resolve [(]chapter 10[)]"
  "not run  ambient occlusion [(]chapters 07, 08[)] [(]no MSAA yet: --msaa 1 runs it[)]"
  -- ${P10} --headless --mode whole --size 64x36 --msaa 4 --out ${CMAKE_BINARY_DIR}/out/10_msaa_plan.png)
set_tests_properties(10_frame.whole_msaa_says_what_it_does_not_run PROPERTIES TIMEOUT 300)
lightpass_program_test(10_frame.msaa_in_the_glass_study_is_refused 2 "--msaa 4 is an option of the whole frame"
  ${P10} --headless --mode frame --size 64x36 --msaa 4 --out ${CMAKE_BINARY_DIR}/out/10_msaa_frame.png)
lightpass_program_test(10_frame.msaa_bad_samples 2 "msaa" ${P10} --msaa 3)
lightpass_program_test(10_frame.sweep_bad_part 2 "--part must be all, transparency, msaa, tubes or whole-msaa" $<TARGET_FILE:10_frame_sweep> --part everything)
# --bench's standard output is its JSON alone, even for a scene the loader has notes about (the
# street's glass: the note goes to standard error).
lightpass_program_test(10_frame.bench_output_is_json_beside_scene_notes 0 "^valid JSON of assets/street_shop/street_shop.gltf$"
  python3 ${CMAKE_CURRENT_SOURCE_DIR}/stdout_is_json.py ${P10} --bench --frames 1 --size 64x36)

# The chapter's exercises (main.cpp's list; the book's "Exercises"): solutions pass, stubs fail.
lightpass_exercise_tests(10_frame 3)
