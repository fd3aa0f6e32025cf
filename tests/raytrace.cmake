# The ray-traced ground truth (common/raytrace.h): on the CPU, and against the rasteriser on
# a headless context. Every test is named common.raytrace.*, so `ctest -R '^common\.raytrace\.'`
# runs them.
lightpass_gtests(common.raytrace unit lightpass_raytrace unit/test_raytrace.cpp)
lightpass_gtests(common.raytrace gl "lightpass_raytrace;lightpass_02_gbuffer" unit/test_raytrace_gl.cpp)

# The throughput benchmark (book/00-introduction.md): bad input, and a run that writes its CSV.
set(RAYTRACE_BENCH $<TARGET_FILE:raytrace_bench>)
lightpass_program_test(common.raytrace.bench_bad_radius 2 "--radius must be a length in metres above 0, not '-1'" ${RAYTRACE_BENCH} --radius -1)
lightpass_program_test(common.raytrace.bench_unknown_option 2 "unknown option '--frobnicate'" ${RAYTRACE_BENCH} --frobnicate)
lightpass_program_test(common.raytrace.bench_smoke_writes_csv 0 "wrote .*00_raytrace_smoke.csv"
  ${RAYTRACE_BENCH} --seconds 1 --size 32x18 --samples 2 --machine smoke --out ${CMAKE_BINARY_DIR}/out)

# The introduction's GPU probe (tools/gpu_probe): a smoke test (it runs and writes its four
# rows; the rates on llvmpipe mean nothing) and its bad input.
add_test(NAME tools.gpu_probe_smoke_writes_four_rows COMMAND ${EXPECT} 0
  ",arithmetic,fragment,32,18,32," ",arithmetic,compute,32,18,32," ",fill,fragment,32,18,2," ",fill,compute,32,18,2,"
  -- $<TARGET_FILE:gpu_probe> --size 32x18 --iterations 8 --layers 2 --runs 1)
lightpass_program_test(tools.gpu_probe_unknown_option 2 "unknown option --frobnicate" $<TARGET_FILE:gpu_probe> --frobnicate)
lightpass_program_test(tools.gpu_probe_bad_size 2 "--size must be WxH" $<TARGET_FILE:gpu_probe> --size 0x5)
lightpass_program_test(tools.gpu_probe_bad_number 2 "--iterations must be a whole number between 1 and 2.20, not 'x'" $<TARGET_FILE:gpu_probe> --iterations x)
