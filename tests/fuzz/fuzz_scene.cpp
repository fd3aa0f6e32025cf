// libFuzzer target for the scene loader (tools/fuzz-scene builds and runs it): any bytes, as a
// .gltf or a .glb, must give a Scene or an lp::Error, never a crash, a hang or a leak. Only the
// CPU side runs (load_scene_from_memory needs no GL context). Relative URIs are looked up in
// the current directory, which tools/fuzz-scene makes an empty one. The limits are smaller
// than a reader's (SceneLimits): the fuzzer explores the checks, and the bounded work the
// full limits allow (a second in Release) would take minutes under the sanitizers.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/error.h"
#include "common/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<unsigned char> bytes(data, data + size);
  const lp::SceneLimits limits{.max_file_bytes = 16 << 20, .max_instances = 20'000, .max_node_visits = 80'000,
                               .max_lights = 2'000, .max_cameras = 1'000, .max_node_extras = 2'000, .max_name_bytes = 16 << 20,
                               .max_vertices = 1 << 20, .max_indices = 4 << 20, .max_image_side = 4096, .max_image_texels = 4 << 20};
  try {
    lp::Scene scene = lp::load_scene_from_memory(bytes, "fuzz/input.gltf", limits);
  } catch (const lp::Error&) {
    // A clear refusal is the right answer to a bad file. Anything else escapes and is a finding.
  }
  return 0;
}
