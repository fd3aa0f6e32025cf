// The book's scenes and the loader test inputs.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace scenegen {

// Writes out_dir/<name>/<name>.gltf, .bin and textures; the directory is emptied first.
void write_forward(const std::filesystem::path& out_dir);
void write_atrium(const std::filesystem::path& out_dir);
void write_street(const std::filesystem::path& out_dir);
void write_cornell(const std::filesystem::path& out_dir);
void write_neon(const std::filesystem::path& out_dir);   // chapter 04
void write_street_neon(const std::filesystem::path& out_dir);  // chapter 04: the street with neon signs
void write_street_shop(const std::filesystem::path& out_dir);  // chapter 10: the neon street with shop windows
void write_glass(const std::filesystem::path& out_dir);  // chapter 10: glass panes (alphaMode BLEND) before lit walls

// Small broken / edge-case glTF files for the loader's tests, written into dir.
void write_test_data(const std::filesystem::path& dir);

// Loads every .gltf under dir with tinygltf and checks it against the lightpass conventions.
// Returns the number of problems found (0: all good); prints a summary per scene.
int verify_assets(const std::filesystem::path& dir);
// Checks that each test input fails (or loads) the way tests/data/README.md says.
int verify_test_data(const std::filesystem::path& dir);

}  // namespace scenegen
