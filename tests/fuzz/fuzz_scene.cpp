// libFuzzer target for the scene loader (tools/fuzz-scene builds and runs it): any bytes, as a
// .gltf or a .glb, must give a Scene or an lp::Error, never a crash, a hang or a leak. Only the
// CPU side runs (load_scene_from_memory needs no GL context). Relative URIs are looked up in
// the current directory, which tools/fuzz-scene makes an empty one. The limits are the
// program's (SceneLimits{}): a finding past smaller ones would not be the program's, and one
// the program's limits allow (memory, time) is a finding too; tools/fuzz-scene's memory and
// time limits are set from them.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/error.h"
#include "common/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<unsigned char> bytes(data, data + size);
  const lp::SceneLimits limits{};
  try {
    lp::Scene scene = lp::load_scene_from_memory(bytes, "fuzz/input.gltf", limits);
  } catch (const lp::Error&) {
    // A clear refusal is the right answer to a bad file. Anything else escapes and is a finding.
  }
  return 0;
}
