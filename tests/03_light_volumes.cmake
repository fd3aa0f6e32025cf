# Chapter 03: light volumes with stencil. Unit tests of the maths (no OpenGL), GPU tests on
# a headless context (cross-checks, exact fragment counts), and the program itself.

lightpass_gtests(03_light_volumes unit lightpass_03_light_volumes unit/test_03_light_volumes.cpp)
lightpass_gtests(03_light_volumes gl lightpass_03_light_volumes unit/test_03_light_volumes_gl.cpp
  unit/test_03_twins_gl.cpp unit/glsl_twin.cpp)

# The program: reference images (every strategy, the hard cases, deferred lighting and the
# book's pictures), outputs and bad input.
set(P03 $<TARGET_FILE:03_light_volumes>)
foreach(mode stencil full-screen scissor front-faces back-faces stencil-bits light-prepass light-prepass-chroma)
  lightpass_program_test(03_light_volumes.reference.${mode} 0 "references match" ${P03} --check --mode ${mode} --out ${CHECK_OUT}/03_light_volumes)
endforeach()
lightpass_program_test(03_light_volumes.headless_says_what_it_shaded 0 "frame took .* ms.*fragments shaded [0-9]+, lit [0-9]+, overshading"
  ${P03} --headless --size 160x90 --out ${CMAKE_BINARY_DIR}/out/03_headless.png)
lightpass_program_test(03_light_volumes.bench_prints_json 0 "\"passes\":\\[\\{\"name\":\"geometry: G-buffer"
  ${P03} --bench --frames 2 --size 160x90 --count 0)
# 100 000 lights render (instanced back faces: the stencil strategy's two draws per light take
# about 10 s on llvmpipe), all of them: the program reports 100000 local lights, none skipped,
# fragments shaded and lit, and the image is brighter than with the street's own 312 lights
# (mean 43.3 steps on llvmpipe; with 100 000: 55.5). A frame that drops the lights, or blows
# them out to white, leaves the band.
lightpass_image_test(03_light_volumes.hundred_thousand_lights "100000 local lights, back-faces: frame took [0-9.]+ ms.*fragments shaded [1-9][0-9]*, lit [1-9][0-9]*.*, 0 lights skipped"
  ${CMAKE_BINARY_DIR}/out/03_100k.png --background ${BACKGROUND_SRGB8} --mean 50 62 --lit 0.07 0.2
  RUN ${P03} --headless --size 64x36 --view overview --show result --lights 100000 --mode back-faces --out ${CMAKE_BINARY_DIR}/out/03_100k.png)
# Zero intensity (left out here), a negative intensity and a negative range (left out by the
# loader, the same in every chapter), a 109-degree spot (drawn with a sphere).
add_test(NAME 03_light_volumes.bad_lights_warn_and_render COMMAND ${EXPECT} 0
  "give no light .*'dark' \\(1\\)" "light 'negative' is left out: its intensity -2" "light 'negative_range' is left out: its range -3"
  "90 degrees or more.*'wide_spot'" "^2 local lights"
  -- ${P03} --headless --size 160x90 --scene tests/data/bad_lights.gltf --out ${CMAKE_BINARY_DIR}/out/03_bad_lights.png)
# The opening (./run 03 with nothing given) shows what the volumes do: down the street among the
# lamps' pools of light (the overview is mostly sky), the image's left half beside the right half
# of the fragments the lights' volumes shaded per pixel, captioned, with the heat map's key; the
# README's picture. Below the captions and above the key, the left half is the image's reference
# and the right half the heat map's (an opening without the split, or on another view, fails
# both). The subject: each light shades only the pixels its volume covers, so the stencil-culled
# volumes leave part of the picture unshaded (13 % of the heat half on llvmpipe; every light
# drawn full-screen leaves none) and shade far fewer fragments than every light on every pixel
# (the heat half's mean 71 steps; full-screen 255, the ramp's white): at least 5 % unshaded and a
# mean under half the ramp.
lightpass_image_test(03_light_volumes.opening_shows_the_fragments_the_volumes_shaded "wrote" ${CMAKE_BINARY_DIR}/out/03_opening.png
  --region 0 14 160 166 --matches ${CMAKE_SOURCE_DIR}/tests/reference/03_light_volumes/street_level_stencil.png
  --region 160 14 160 145 --matches ${CMAKE_SOURCE_DIR}/tests/reference/03_light_volumes/street_level_stencil_show-heat-shaded.png
  --lit 0 0.95 --mean 0 128
  RUN ${P03} --headless --size 320x180 --out ${CMAKE_BINARY_DIR}/out/03_opening.png)
lightpass_program_test(03_light_volumes.bad_mode 2 "unknown mode 'tiled'" ${P03} --mode tiled)
lightpass_program_test(03_light_volumes.bad_show 2 "--show must be one of: result diffuse specular volumes stencil-mask heat-shaded heat-lit split. got 'heat'" ${P03} --show heat)
lightpass_program_test(03_light_volumes.no_such_light_to_show 1 "there is no light 5000 to show the stencil mask of \\(312 local lights\\)"
  ${P03} --headless --size 64x36 --show stencil-mask --light 5000 --out ${CMAKE_BINARY_DIR}/out/03_nolight.png)

# The window path (GLFW + the panel) under a virtual X display, closing itself after 3 frames.
# The screenshot is the scene under the panel, not a black window (46 % lit on llvmpipe).
lightpass_image_test(03_light_volumes.window_screenshot "window screenshot, 320x180" ${CMAKE_BINARY_DIR}/out/03_window.png
  --size 320x180 --background ${BACKGROUND_SRGB8} --lit 0.3 1
  RUN xvfb-run -a -s "-screen 0 320x180x24" ${P03} --size 320x180 --frames 3 --out ${CMAKE_BINARY_DIR}/out/03_window.png)

# --bench waits for every frame it reports: with the timer queries that a GPU uses (forced on
# llvmpipe, whose results then arrive after the frame, as on a GPU), --frames 2 reports 2
# frames for the whole run and for every pass, and the geometry pass has a time and fragments.
# (Before the fix it printed before the last frame's queries were back: a pass with 1 frame.)
add_test(NAME 03_light_volumes.bench_reads_back_every_frame_it_reports COMMAND ${EXPECT} 0
  "\"frames\":2,\"warmup_frames\":[0-9]+"
  "\"name\":\"geometry: G-buffer \\(chapter 02\\)\",\"mean_ms\":(0\\.0*[1-9]|[1-9])[^}]*\"fragments\":[1-9][0-9]*,\"frames\":2}"
  "\"name\":\"composite: albedo x L1 \\+ L2 \\+ emissive \\(chapter 03\\)\"[^}]*\"frames\":2}"
  --no-match "\"frames\":([013-9]|[0-9][0-9])"
  -- env LIGHTPASS_TIMER=queries ${P03} --bench --frames 2 --size 160x90 --count 0)
set_tests_properties(03_light_volumes.bench_reads_back_every_frame_it_reports PROPERTIES TIMEOUT 300)
# The stencil strategy's GL_SAMPLES_PASSED ("fragments") includes its marking draws; the bench
# reports the fragments shaded and the marking ones apart, from the chapter's own counters
# (that they add up to GL_SAMPLES_PASSED is LightVolumesGl.SamplesPassedAreShadedPlusMarking).
lightpass_program_test(03_light_volumes.bench_reports_shaded_and_marking_apart 0
  "\"name\":\"local lights: stencil\",[^}]*\"fragments\":[1-9][0-9]*,\"counts\":\\{\"shaded\":[1-9][0-9]*,\"lit\":[1-9][0-9]*,\"marking\":[1-9][0-9]*\\}"
  ${P03} --bench --frames 1 --size 160x90)

# The panel tests below draw the street's overview without the split (a frame 6x cheaper on
# llvmpipe than the opening's split at street level): their subject is the panel.
# The panel at 1280x720 leaves the whole image visible: the window draws it right of the
# panel, pixel for pixel the headless image at that size (tests/window_image_beside_panel.sh).
add_test(NAME 03_light_volumes.window_panel_leaves_the_image_visible
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/window_image_beside_panel.sh ${P03} $<TARGET_FILE:image_stats> ${CMAKE_BINARY_DIR}/out/03_beside_panel
          --view overview --show result)
set_tests_properties(03_light_volumes.window_panel_leaves_the_image_visible PROPERTIES TIMEOUT 300)
# The title bar's triangle folds the panel (one click at one frame a second), and the image
# then fills the window: the program says so.
add_test(NAME 03_light_volumes.window_panel_folds_at_a_slow_frame_rate
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/window_click.sh ${P03} 1280x720 20 19 "^panel: folded, the image fills the window$"
          --view overview --show result)
set_tests_properties(03_light_volumes.window_panel_folds_at_a_slow_frame_rate PROPERTIES TIMEOUT 300)
# An on/off knob is a checkbox, and one click on it (the cursor gone before the next frame, at
# one frame a second) switches it: the panel says "--count 0".
add_test(NAME 03_light_volumes.window_checkbox_at_a_slow_frame_rate
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/window_click.sh ${P03} 1280x720 27 291 "^panel: --count 0$" --view overview --show result)
set_tests_properties(03_light_volumes.window_checkbox_at_a_slow_frame_rate PROPERTIES TIMEOUT 300)
# The panel scrolls as a whole: in a 640x240 window its last knob (--count) starts below the
# window; the mouse wheel over the panel brings it inside, and a click there switches it
# (tests/window_panel.sh, the panel's layout as the program says it at a slow frame rate).
add_test(NAME 03_light_volumes.window_panel_scrolls_to_its_last_knob
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/window_panel.sh ${P03} 640x240 scroll --view overview --show result)
set_tests_properties(03_light_volumes.window_panel_scrolls_to_its_last_knob PROPERTIES TIMEOUT 300)
# In a 320-wide window (a 300-pixel panel) every line of the panel wraps inside it (the
# chapter's counts, the frame times) and a knob's help, hovered, is a tooltip inside the window.
add_test(NAME 03_light_volumes.window_narrow_panel_wraps_its_text
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/window_panel.sh ${P03} 320x480 wrap --view overview --show result)
set_tests_properties(03_light_volumes.window_narrow_panel_wraps_its_text PROPERTIES TIMEOUT 300)

# The chapter's exercises (main.cpp's list; the book's "Exercises"): solutions pass, stubs fail.
lightpass_exercise_tests(03_light_volumes 3)
