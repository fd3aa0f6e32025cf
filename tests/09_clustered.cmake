# Chapter 09: tiled and clustered light culling. Unit tests of the grid maths (no OpenGL),
# GPU tests on a headless context (the cross-check against chapter 03, counts, hard cases).
lightpass_gtests(09_clustered unit lightpass_09_clustered unit/test_09_clustered.cpp)
lightpass_gtests(09_clustered gl lightpass_09_clustered unit/test_09_clustered_gl.cpp unit/test_09_twins_gl.cpp unit/glsl_twin.cpp)

# The program: reference images (every mode, inside a light, the heat maps and the grid).
set(P09 $<TARGET_FILE:09_clustered>)
foreach(mode clustered tiled clustered-fragment tiled-fragment tiled-staged zbin zbin-staged stencil)
  lightpass_program_test(09_clustered.reference.${mode} 0 "references match" ${P09} --check --mode ${mode} --out ${CHECK_OUT}/09_clustered)
endforeach()
# A headless run reports what it did: the street's 312 lights, lit pairs equal to the stencil
# volumes' (69 096 at 320x180 on the overview, the same count in both runs), no light dropped.
lightpass_program_test(09_clustered.headless_reports_lit_pairs_and_no_drops 0
  "312 local lights, clustered: .*lights evaluated [0-9]+, lit 69096, .*3456 cells, [1-9][0-9]* list entries.*dropped 0"
  ${P09} --headless --size 320x180 --view overview --show result --out ${CMAKE_BINARY_DIR}/out/09_headless.png)
lightpass_program_test(09_clustered.stencil_lights_the_same_pairs 0 "312 local lights, stencil: .*lit 69096,"
  ${P09} --headless --size 320x180 --view overview --show result --mode stencil --out ${CMAKE_BINARY_DIR}/out/09_headless_stencil.png)
# The opening (./run 09 with nothing given) shows what culling does: down the street, the
# image's left half beside the right half of the lights each pixel evaluated (its cell's list),
# with captions and a key. Below the captions and above the key, the left half is the image's
# reference and the right half the heat map's own render: an opening without the split, or on
# another view, fails both.
add_test(NAME 09_clustered.opening_heat_map COMMAND ${P09} --headless --size 320x180 --view street_level
         --show heat-evaluated --out ${CMAKE_BINARY_DIR}/out/09_opening_heat.png)
set_tests_properties(09_clustered.opening_heat_map PROPERTIES FIXTURES_SETUP opening09)
lightpass_image_test(09_clustered.opening_shows_the_lights_evaluated_beside_the_image "wrote" ${CMAKE_BINARY_DIR}/out/09_opening.png
  --region 0 14 160 166 --matches ${CMAKE_SOURCE_DIR}/tests/reference/09_clustered/street_level_clustered.png
  --region 160 14 160 145 --matches ${CMAKE_BINARY_DIR}/out/09_opening_heat.png
  RUN ${P09} --headless --size 320x180 --out ${CMAKE_BINARY_DIR}/out/09_opening.png)
set_tests_properties(09_clustered.opening_shows_the_lights_evaluated_beside_the_image PROPERTIES FIXTURES_REQUIRED opening09)
lightpass_program_test(09_clustered.bad_mode 2 "unknown mode 'forward'" ${P09} --mode forward)
# zbin-staged's lanes (four invocations a pixel by default): a shape the pass cannot take is
# refused with the reason, not a shader link error or a wrong image.
lightpass_program_test(09_clustered.zbin_staged_lanes_need_small_tiles 1
  "zbin-staged with 4 invocations a pixel needs tiles of at most 16 pixels, not 32 \\(one lane for those\\)"
  ${P09} --headless --size 64x36 --mode zbin-staged --tile 32 --out ${CMAKE_BINARY_DIR}/out/09_lanes_tile32.png)
lightpass_program_test(09_clustered.zbin_staged_three_lanes_refused 1 "takes 1, 2 or 4 invocations a pixel, not 3"
  ${P09} --headless --size 64x36 --mode zbin-staged --lanes 3 --out ${CMAKE_BINARY_DIR}/out/09_lanes_3.png)
# --bench times the three passes apart, under the names the sweep reads.
lightpass_program_test(09_clustered.bench_times_the_three_passes 0
  "\"name\":\"local lights: clustered: depth bounds\".*\"name\":\"local lights: clustered: assign\".*\"name\":\"local lights: clustered: shade\",[^}]*\"counts\":\\{\"evaluated\":[1-9][0-9]*,\"lit\":[1-9][0-9]*\\}"
  ${P09} --bench --frames 2 --size 160x90)
# Without subgroup operations the compute shading takes the fallback (today's loop) and says so.
lightpass_program_test(09_clustered.no_subgroups_takes_the_fallback_and_says_so 0
  "subgroups: none \\(fallback\\) \\(0 of [1-9][0-9]* pixels from a shared list\\)"
  env LIGHTPASS_TEST_NO_SUBGROUPS=1 ${P09} --headless --size 64x36 --mode tiled --out ${CMAKE_BINARY_DIR}/out/09_no_subgroups.png)
# A grid too large for its bounds is refused with a message, not allocated.
lightpass_program_test(09_clustered.huge_grid_is_refused 1 "a grid of 1024 x 1024 x 256 cells is more than 4 194 304"
  ${P09} --headless --size 1024x1024 --clusters-x 1024 --clusters-y 1024 --slices 256 --out ${CMAKE_BINARY_DIR}/out/09_huge.png)
# Z-binning's tile masks (a bit per light per tile) are bounded: too many for their bound is
# refused with a message naming the knob, not allocated.
lightpass_program_test(09_clustered.zbin_masks_over_their_bound_are_refused 1
  "Z-binning's tile masks, 230400 tiles x 100000 lights, take more than 1 GiB; use larger tiles"
  ${P09} --headless --size 640x360 --mode zbin --tile 1 --lights 100000 --out ${CMAKE_BINARY_DIR}/out/09_zbin_huge.png)
# The staged pass runs a work group per tile: tiles larger than 32 pixels are refused by name.
lightpass_program_test(09_clustered.staged_needs_tiles_of_at_most_32_pixels 1
  "tiled-staged needs square tiles of at most 32 pixels, not 64 x 64"
  ${P09} --headless --size 160x90 --mode tiled-staged --tile 64 --out ${CMAKE_BINARY_DIR}/out/09_staged64.png)
# The window path (GLFW + the panel) under a virtual X display, closing itself after 3 frames.
# A smoke test: at 320x180 the panel covers most of the window, so the lit fraction says the
# window drew, not that the street is under it (the references check the street).
lightpass_image_test(09_clustered.window_smoke_screenshot "window screenshot, 320x180" ${CMAKE_BINARY_DIR}/out/09_window.png
  --size 320x180 --background ${BACKGROUND_SRGB8} --lit 0.3 1
  RUN xvfb-run -a -s "-screen 0 320x180x24" ${P09} --size 320x180 --frames 3 --out ${CMAKE_BINARY_DIR}/out/09_window.png)
# Clustered forward: the opaque street drawn forward from the cluster lists equals the deferred.
lightpass_gtests(09_clustered_forward gl lightpass_09_clustered unit/test_09_clustered_forward_gl.cpp)
# The fair benchmark (--density): the lights scaled until the surface pixels see the target
# density (within the fit's 3 %), each method timed on each view, the summary's row naming
# what measured it; no warning that a density was missed or a list overflowed.
set(SWEEP09_OUT ${CMAKE_BINARY_DIR}/out/09_density)
add_test(NAME 09_clustered.density_sweep_reaches_its_density COMMAND ${EXPECT} 0
  "^target_density,lights,method,grid,range_scale,density,lit,evaluated_per_lit,local_median_ms,local_p95_ms,"
  "^8,1000,tiled,default,[0-9.]+,(7\\.(7[6-9]|[89])|8\\.([01]|2[0-4]))[0-9]*,[1-9][0-9]*,[0-9.]+,[0-9.e-]+,[0-9.e-]+,.*,2,[^,]+.*,64,36,1$"
  "^32,1000,clustered,default,[0-9.]+,(31\\.|32\\.|30\\.[4-9])[0-9]*,"
  # Z-binning and the floor measured too; the floor's shading is 1 x its own.
  "^32,1000,zbin,default,[0-9.]+,(31\\.|32\\.|30\\.[4-9])[0-9]*,"
  "^32,1000,zbin-staged,default,[0-9.]+,(31\\.|32\\.|30\\.[4-9])[0-9]*,"
  "^32,1000,zbin-staged,sub-blocks,[0-9.]+,(31\\.|32\\.|30\\.[4-9])[0-9]*,"
  "^32,1000,zbin-staged,fields,[0-9.]+,(31\\.|32\\.|30\\.[4-9])[0-9]*,"
  "^32,1000,zbin-staged,lanes 1,[0-9.]+,(31\\.|32\\.|30\\.[4-9])[0-9]*,"
  "^32,1000,zbin-staged,lanes 2,[0-9.]+,(31\\.|32\\.|30\\.[4-9])[0-9]*,"
  "^32,1000,zbin-staged,lanes 4,[0-9.]+,(31\\.|32\\.|30\\.[4-9])[0-9]*,"
  "^32,1000,zbin-floor,default,([0-9.e-]+,){10}1,"
  # The CPU's time per frame beside the GPU's, and Z-binning's assignment by its parts (the
  # clears, the sort, the bins, the tiles; the floor's exact lists only in zbin-floor).
  "^32,1000,zbin,default,([^,]+,){13}[0-9.]*[1-9][0-9.e-]*,[0-9.e-]+,([0-9.]*[1-9][0-9.e-]*,){3}0,"
  "^32,1000,zbin-floor,default,([^,]+,){18}[0-9.]*[1-9][0-9.e-]*,"
  "^32,1000,tiled,default,([^,]+,){13}[0-9.]*[1-9][0-9.e-]*,0,0,0,0,0,"
  --no-match "warning: .*(not 8|not 32|overflow|lists over| at [0-9]+ lights: )"
  -- sh -c "$<TARGET_FILE:09_clustered_sweep> --density --out ${SWEEP09_OUT} --size 64x36 --max-lights 1000 --views 2 --frames 1 2>&1 && cat ${SWEEP09_OUT}/09_density_summary_llvmpipe.csv")
set_tests_properties(09_clustered.density_sweep_reaches_its_density PROPERTIES TIMEOUT 300)
# The grid sweep (--grid): each grid of each method at the target density, named in the summary.
set(GRID09_OUT ${CMAKE_BINARY_DIR}/out/09_grid)
add_test(NAME 09_clustered.grid_sweep_names_every_grid COMMAND ${EXPECT} 0
  "^target_density,lights,method,grid,"
  "^8,1000,tiled,tile 8,"  "^8,1000,tiled,tile 32,"  "^8,1000,clustered,60x34x96,"
  "^8,1000,clustered,16x9x24 near 2,"  "^8,1000,clustered,16x9x96 near 10,"
  "^8,1000,zbin,tile 64 bins 4096,[0-9.]+,(7\\.(7[6-9]|[89])|8\\.([01]|2[0-4]))[0-9]*,"
  # Z-binning staged at each tile size, 32 pixels too (a group of 1 024 invocations), with and
  # without the sub-blocks, and at 256 and 4 096 bins; no method may fail (a shader that does not link is warned so).
  "^8,1000,zbin-staged,tile 8 bins 1024,"  "^8,1000,zbin-staged,tile 32 bins 1024 sub-blocks,"
  "^8,1000,zbin-staged,tile 16 bins 256,"  "^8,1000,zbin-staged,tile 16 bins 4096,"
  --no-match "warning: .*(not 8|overflow|lists over|not timed| at [0-9]+ lights: )"
  -- sh -c "$<TARGET_FILE:09_clustered_sweep> --grid --target 8 --out ${GRID09_OUT} --size 64x36 --max-lights 1000 --views 1 --frames 1 2>&1 && cat ${GRID09_OUT}/09_grid_d8_summary_llvmpipe.csv")
set_tests_properties(09_clustered.grid_sweep_names_every_grid PROPERTIES TIMEOUT 300)
# The subgroup sweep (--subgroups): each path's light buffers and counts against the fallback's
# (it exits 1 when they differ), the path named in the summary's grid column.
set(SUB09_OUT ${CMAKE_BINARY_DIR}/out/09_subgroups)
add_test(NAME 09_clustered.subgroup_sweep_equals_the_fallback COMMAND ${EXPECT} 0
  "tiled, street_level[^:]*: [^:]* against the fallback: identical"
  "clustered, street_level[^:]*: [^:]* against the fallback: identical"
  "^32,1000,tiled,fallback,"  "^32,1000,clustered,(subgroups [A-Za-z_]+|fallback),"
  --no-match "DIFFERENT|warning: .*(overflow|lists over|not timed)"
  -- sh -c "$<TARGET_FILE:09_clustered_sweep> --subgroups --out ${SUB09_OUT} --size 64x36 --max-lights 1000 --views 1 --frames 1 2>&1 && cat ${SUB09_OUT}/09_subgroups_summary_llvmpipe.csv")
set_tests_properties(09_clustered.subgroup_sweep_equals_the_fallback PROPERTIES TIMEOUT 300)
# The phase sweep (--phases): zbin-staged's cycles by phase, with and without the sub-blocks: every
# phase timed but the blocks' own without them, and the shares of a method summing to one.
set(PHASES09_OUT ${CMAKE_BINARY_DIR}/out/09_phases)
add_test(NAME 09_clustered.phase_sweep_times_every_phase COMMAND ${EXPECT} 0
  "^32,1000,zbin-staged,phase clocks,setup,[1-9][0-9]*,"  "^32,1000,zbin-staged,phase clocks,shade,[1-9][0-9]*,0\\.[1-9]"
  "^32,1000,zbin-staged,phase clocks,reach,0,0,"  "^32,1000,zbin-staged,sub-blocks phase clocks,reach,[1-9][0-9]*,"
  "^shares: phase clocks 1\\.000, sub-blocks phase clocks 1\\.000$"
  --no-match "warning"
  -- sh -c "$<TARGET_FILE:09_clustered_sweep> --phases --target 32 --out ${PHASES09_OUT} --size 64x36 --max-lights 1000 --views 1 --frames 1 2>&1 && cat ${PHASES09_OUT}/09_phases_d32_cycles_llvmpipe.csv && awk -F, '/^32,/ { s[$4] += $7 } END { printf \"shares: phase clocks %.3f, sub-blocks phase clocks %.3f\\n\", s[\"phase clocks\"], s[\"sub-blocks phase clocks\"] }' ${PHASES09_OUT}/09_phases_d32_cycles_llvmpipe.csv")
set_tests_properties(09_clustered.phase_sweep_times_every_phase PROPERTIES TIMEOUT 300)
# The lane sweep (--lanes): zbin-staged with one lane, four in every tile and four in the tiles of
# at least N lights, a row each; a smoke test of the sweep (the lanes' images: ZBinStaged*).
set(LANES09_OUT ${CMAKE_BINARY_DIR}/out/09_lanes)
add_test(NAME 09_clustered.lane_sweep_smoke_names_every_threshold COMMAND ${EXPECT} 0
  "^32,1000,zbin-floor,default,"  "^32,1000,zbin-staged,lanes 1,"  "^32,1000,zbin-staged,lanes 4,"
  "^32,1000,zbin-staged,lanes 4 from 256,"  "^32,1000,zbin-staged,lanes 4 from 16384,"
  --no-match "warning: .*(not 32|overflow|lists over|not timed| at [0-9]+ lights: )"
  -- sh -c "$<TARGET_FILE:09_clustered_sweep> --lanes --target 32 --out ${LANES09_OUT} --size 64x36 --max-lights 1000 --views 1 --frames 1 2>&1 && cat ${LANES09_OUT}/09_lanes_d32_summary_llvmpipe.csv")
set_tests_properties(09_clustered.lane_sweep_smoke_names_every_threshold PROPERTIES TIMEOUT 300)
add_test(NAME 09_clustered.phase_sweep_alone COMMAND ${EXPECT} 2 "--grid, --subgroups, --phases and --lanes: one at a time"
  -- $<TARGET_FILE:09_clustered_sweep> --grid --phases --out ${PHASES09_OUT}/bad)
add_test(NAME 09_clustered.density_sweep_bad_views COMMAND ${EXPECT} 1 "--views: 1 to 64, not 0"
  -- $<TARGET_FILE:09_clustered_sweep> --density --views 0)
# --modes and --min-lights: the named modes' methods and the floor alone, from the count given;
# no warning that the density was missed, a list overflowed or a method went untimed (the
# density test's list: a warning that frame times had not settled is the machine's load, not
# the sweep's).
set(MODES09_OUT ${CMAKE_BINARY_DIR}/out/09_modes)
add_test(NAME 09_clustered.density_sweep_modes_and_min_lights COMMAND ${EXPECT} 0
  "^8,10000,zbin-floor,default,"  "^8,10000,zbin-staged,default,"  "^8,10000,zbin-staged,sub-blocks,"
  "^8,10000,zbin-staged,fields,"  "^8,10000,zbin-staged,lanes 1,"  "^8,10000,zbin-staged,lanes 2,"
  "^8,10000,zbin-staged,lanes 4,"
  --no-match "^8,1000,|^8,10000,(tiled|clustered|zbin,)|warning: .*(not 8|overflow|lists over| at [0-9]+ lights: )"
  -- sh -c "$<TARGET_FILE:09_clustered_sweep> --density --target 8 --modes zbin-staged --min-lights 10000 --out ${MODES09_OUT} --size 64x36 --max-lights 10000 --views 1 --frames 1 2>&1 && cat ${MODES09_OUT}/09_density_d8_summary_llvmpipe.csv")
set_tests_properties(09_clustered.density_sweep_modes_and_min_lights PROPERTIES TIMEOUT 300)
add_test(NAME 09_clustered.density_sweep_bad_mode COMMAND ${EXPECT} 2 "--modes: 'zbin-stagd' is no mode of chapter 9"
  -- $<TARGET_FILE:09_clustered_sweep> --density --modes zbin,zbin-stagd --out ${MODES09_OUT}/bad --size 64x36 --max-lights 1000 --views 1 --frames 1)
# The chapter's exercises (main.cpp's list; the book's "Exercises"): solutions pass, stubs fail,
# and a plausible wrong answer to each (tests/exercises/wrong/09_clustered/) fails. Exercise 4's
# answer is a number.
lightpass_exercise_tests(09_clustered 4 NUMBERS 4 WRONG 1 2 3 4)
