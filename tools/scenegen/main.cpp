// scenegen: writes the lightpass scenes (glTF 2.0) and the loader test inputs, deterministically.
//
//   scenegen OUT_DIR                    writes OUT_DIR/{forward,atrium,street,cornell,neon,street_neon,street_shop,glass}/
//   scenegen --test-data DIR            writes the loader test inputs into DIR
//   scenegen --verify DIR               loads every .gltf under DIR with tinygltf and checks it
//   scenegen --verify-test-data DIR     checks the test inputs fail/load as documented
#include <cstdio>
#include <exception>
#include <string>

#include "scenes.h"

int main(int argc, char** argv) {
  const std::string usage =
      "usage: scenegen OUT_DIR | --test-data DIR | --verify DIR | --verify-test-data DIR\n";
  if (argc != 2 && argc != 3) {
    std::fputs(usage.c_str(), stderr);
    return 2;
  }
  try {
    const std::string a = argv[1];
    if (argc == 2 && a.rfind("--", 0) != 0) {
      scenegen::write_forward(a);
      scenegen::write_atrium(a);
      scenegen::write_street(a);
      scenegen::write_cornell(a);
      scenegen::write_neon(a);
      scenegen::write_street_neon(a);
      scenegen::write_street_shop(a);
      scenegen::write_glass(a);
      return 0;
    }
    if (argc == 3 && a == "--test-data") {
      scenegen::write_test_data(argv[2]);
      return 0;
    }
    if (argc == 3 && a == "--verify") return scenegen::verify_assets(argv[2]) == 0 ? 0 : 1;
    if (argc == 3 && a == "--verify-test-data") return scenegen::verify_test_data(argv[2]) == 0 ? 0 : 1;
    std::fputs(usage.c_str(), stderr);
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "scenegen: %s\n", e.what());
    return 1;
  }
}
