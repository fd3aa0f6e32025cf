# Chapter 09: tiled and clustered light culling. Unit tests of the grid maths (no OpenGL),
# GPU tests on a headless context (the cross-check against chapter 03, counts, hard cases).
lightpass_gtests(09_clustered unit lightpass_09_clustered unit/test_09_clustered.cpp)
lightpass_gtests(09_clustered gl lightpass_09_clustered unit/test_09_clustered_gl.cpp)

# The program: reference images (every mode, inside a light, the heat maps and the grid).
set(P09 $<TARGET_FILE:09_clustered>)
foreach(mode clustered tiled clustered-fragment tiled-fragment stencil)
  lightpass_program_test(09_clustered.reference.${mode} 0 "references match" ${P09} --check --mode ${mode} --out ${CHECK_OUT}/09_clustered)
endforeach()
# A headless run reports what it did: the street's 312 lights, lit pairs equal to the stencil
# volumes' (69 096 at 320x180 on the overview, the same count in both runs), no light dropped.
lightpass_program_test(09_clustered.headless_reports_lit_pairs_and_no_drops 0
  "312 local lights, clustered: .*lights evaluated [0-9]+, lit 69096, .*3456 cells, [1-9][0-9]* list entries.*dropped 0"
  ${P09} --headless --size 320x180 --out ${CMAKE_BINARY_DIR}/out/09_headless.png)
lightpass_program_test(09_clustered.stencil_lights_the_same_pairs 0 "312 local lights, stencil: .*lit 69096,"
  ${P09} --headless --size 320x180 --mode stencil --out ${CMAKE_BINARY_DIR}/out/09_headless_stencil.png)
lightpass_program_test(09_clustered.bad_mode 2 "unknown mode 'forward'" ${P09} --mode forward)
