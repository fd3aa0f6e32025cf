// Small broken and edge-case glTF inputs for the loader's tests (tests/data). Each is built
// like the real scenes and then damaged in one way; tests/data/README.md lists them.
#include <array>
#include <cstring>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>

#include <stb_image_write.h>

#include "gltf_writer.h"
#include "mesh.h"
#include "scenes.h"
#include "textures.h"

namespace scenegen {

namespace fs = std::filesystem;

namespace {

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f << text;
  if (!f) throw std::runtime_error("cannot write " + path.string());
}

Material plain(const char* name) {
  Material m;
  m.name = name;
  m.base_color = {0.8f, 0.8f, 0.8f, 1.0f};
  m.roughness = 0.5f;
  return m;
}

// A 2 x 2 m plane, a point light 2 m above it and (optionally) a camera looking at it.
void plane_scene(GltfBuilder& b, const Mesh& plane, int material, bool camera) {
  if (camera) b.add_camera("view", {0.0f, 2.0f, 4.0f}, {0.0f, 0.0f, 0.0f}, 0.8f, 0.05f, 50.0f);
  b.add_point_light("light", {0.0f, 2.0f, 0.0f}, {1.0f, 1.0f, 1.0f}, 2.0f);
  b.add_rect_node("plane", b.add_mesh("plane", plane, material), glm::vec3(0.0f), glm::mat3(1.0f), 2.0f, 2.0f);
}

void write_bytes(const fs::path& path, const std::vector<uint8_t>& bytes) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  if (!f) throw std::runtime_error("cannot write " + path.string());
}

void write_doc(const fs::path& dir, const std::string& name, const json& doc) {
  write_text(dir / (name + ".gltf"), format_json(doc));
}

// minimal.gltf's document, its buffer still minimal.bin: a variant damaged in one place.
json minimal_doc() {
  GltfBuilder b("minimal");
  plane_scene(b, make_rect(2.0f, 2.0f), b.add_material(plain("grey")), true);
  return b.document("minimal.bin");
}

json& camera_node(json& doc) {
  for (auto& n : doc["nodes"])
    if (n.contains("camera")) return n;
  throw std::runtime_error("no camera node");
}

void add_extension(json& doc, const std::string& name, bool required) {
  doc["extensionsUsed"].push_back(name);
  if (required) doc["extensionsRequired"].push_back(name);
}

// A .glb: 12-byte header, the JSON chunk (padded with spaces), the BIN chunk (padded with 0).
std::vector<uint8_t> glb(json doc, std::vector<uint8_t> bin) {
  doc["buffers"][0].erase("uri");
  std::string text = doc.dump();
  while (text.size() % 4) text += ' ';
  while (bin.size() % 4) bin.push_back(0);
  std::vector<uint8_t> out;
  auto u32 = [&](uint32_t v) { for (int i = 0; i < 4; ++i) out.push_back(uint8_t(v >> (8 * i))); };
  out.insert(out.end(), {'g', 'l', 'T', 'F'});
  u32(2);
  u32(uint32_t(12 + 8 + text.size() + 8 + bin.size()));
  u32(uint32_t(text.size()));
  u32(0x4E4F534Au);  // "JSON"
  out.insert(out.end(), text.begin(), text.end());
  u32(uint32_t(bin.size()));
  u32(0x004E4942u);  // "BIN"
  out.insert(out.end(), bin.begin(), bin.end());
  return out;
}

// A 16-bit RGB PNG (stb_image_write writes only 8 bits): stored (uncompressed) deflate blocks.
std::vector<uint8_t> png16(int w, int h) {
  auto crc32 = [](const uint8_t* p, size_t n, uint32_t c = 0xFFFFFFFFu) {
    for (size_t i = 0; i < n; ++i) {
      c ^= p[i];
      for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return c;
  };
  std::vector<uint8_t> raw;
  for (int y = 0; y < h; ++y) {
    raw.push_back(0);  // filter: none
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) {
        uint16_t v = uint16_t(((x + y + c) & 1) ? 0xFFFF : 0x2000);
        raw.push_back(uint8_t(v >> 8));
        raw.push_back(uint8_t(v & 0xFF));
      }
  }
  std::vector<uint8_t> z = {0x78, 0x01};
  uint32_t a = 1, b = 0;
  for (uint8_t v : raw) { a = (a + v) % 65521; b = (b + a) % 65521; }
  for (size_t off = 0; off < raw.size() || off == 0; off += 65535) {
    size_t len = std::min<size_t>(65535, raw.size() - off);
    z.push_back(off + len >= raw.size() ? 1 : 0);
    z.push_back(uint8_t(len)); z.push_back(uint8_t(len >> 8));
    z.push_back(uint8_t(~len)); z.push_back(uint8_t(~len >> 8));
    z.insert(z.end(), raw.begin() + std::ptrdiff_t(off), raw.begin() + std::ptrdiff_t(off + len));
    if (off + len >= raw.size()) break;
  }
  uint32_t adler = (b << 16) | a;
  for (int i = 3; i >= 0; --i) z.push_back(uint8_t(adler >> (8 * i)));
  std::vector<uint8_t> out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  auto chunk = [&](const char* type, const std::vector<uint8_t>& data) {
    uint32_t n = uint32_t(data.size());
    for (int i = 3; i >= 0; --i) out.push_back(uint8_t(n >> (8 * i)));
    std::vector<uint8_t> td(type, type + 4);
    td.insert(td.end(), data.begin(), data.end());
    out.insert(out.end(), td.begin(), td.end());
    uint32_t c = ~crc32(td.data(), td.size());
    for (int i = 3; i >= 0; --i) out.push_back(uint8_t(c >> (8 * i)));
  };
  std::vector<uint8_t> ihdr;
  for (uint32_t v : {uint32_t(w), uint32_t(h)})
    for (int i = 3; i >= 0; --i) ihdr.push_back(uint8_t(v >> (8 * i)));
  ihdr.insert(ihdr.end(), {16, 2, 0, 0, 0});  // 16 bits, RGB
  chunk("IHDR", ihdr);
  chunk("IDAT", z);
  chunk("IEND", {});
  return out;
}

void write_png_rgb(const fs::path& path, int w, int h, const std::vector<uint8_t>& rgb) {
  if (!stbi_write_png(path.string().c_str(), w, h, 3, rgb.data(), w * 3)) throw std::runtime_error("cannot write " + path.string());
}

// A cube of 8 shared corners and 12 triangles (counter-clockwise seen from outside), POSITION only.
Mesh shared_corner_cube() {
  Mesh m;
  for (int i = 0; i < 8; ++i) m.positions.push_back({(i & 1) ? 0.5f : -0.5f, (i & 2) ? 0.5f : -0.5f, (i & 4) ? 0.5f : -0.5f});
  const int faces[6][4] = {{1, 3, 7, 5}, {0, 4, 6, 2}, {2, 6, 7, 3}, {0, 1, 5, 4}, {4, 5, 7, 6}, {0, 2, 3, 1}};
  const glm::vec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int f = 0; f < 6; ++f) {
    uint32_t a = faces[f][0], b = faces[f][1], c = faces[f][2], d = faces[f][3];
    glm::vec3 n = glm::cross(m.positions[b] - m.positions[a], m.positions[c] - m.positions[a]);
    if (glm::dot(n, normals[f]) < 0) std::swap(b, d);
    for (uint32_t i : {a, b, c, a, c, d}) m.indices.push_back(i);
  }
  return m;
}

const char* kReadme = R"md(# tests/data: loader test inputs

Generated by `tools/scenegen` (`scenegen --test-data tests/data`, run by
`tools/regenerate-assets`); do not edit by hand. Each file is small and damaged in exactly
one way. `scenegen --verify-test-data tests/data` checks that tinygltf 2.7 treats them as
listed under "tinygltf".

| file | what it is | tinygltf |
| --- | --- | --- |
| `minimal.gltf` (+ `.bin`) | valid control: 2 x 2 m plane (rect shape), point light, camera `view` | loads, no warnings |
| `empty_file.gltf` | 0 bytes | fails |
| `malformed.gltf` | `minimal.gltf` truncated half way (invalid JSON) | fails |
| `missing_buffer.gltf` | valid JSON whose buffer uri `missing_buffer.bin` does not exist | fails ("File not found") |
| `missing_texture.gltf` (+ `.bin`) | valid; the material's baseColorTexture image uri `missing_texture.png` does not exist | loads with a warning, image data empty |
| `nonindexed_nonormals.gltf` (+ `.bin`) | cube as 36-vertex triangle soup: POSITION only (no indices, normals, tangents, UVs), no material; camera `view`, point light | loads, no warnings |
| `no_camera.gltf` (+ `.bin`) | valid plane + point light, no camera | loads, no warnings |
| `bad_index.gltf` (+ `.bin`) | plane whose index accessor refers to vertex 99 of 4 | loads, no warnings (tinygltf does not check indices) |

Real-model cases and hostile inputs (not checked by `--verify-test-data`; the loader's tests
say what each must give). Files without their own `.bin` use `minimal.bin`.

| file | what it is |
| --- | --- |
| `no_camera_no_lights.gltf` (+ `.bin`) | a 1 m box (with normals) and nothing else: no camera, no lights |
| `box_on_floor.gltf` (+ `.bin`) | a red 1 m box standing on a 6 x 6 m floor of grey 0.6, no camera, no lights: the default rig's shadow |
| `indexed_nonormals.gltf` (+ `.bin`) | cube of 8 shared corners, 36 indices, POSITION only: must be flat shaded |
| `strip_fan.gltf` (+ `.bin`) | a quad as TRIANGLE_STRIP (4 vertices) and one as TRIANGLE_FAN (6), camera, light |
| `points_only.gltf` (+ `.bin`) | one POINTS primitive: nothing to draw |
| `lines_and_triangles.gltf` | minimal's plane plus a LINES primitive |
| `requires_draco.gltf` | minimal with KHR_draco_mesh_compression in extensionsRequired |
| `requires_meshopt.gltf` | minimal with EXT_meshopt_compression in extensionsRequired |
| `uses_clearcoat.gltf` | minimal whose material uses KHR_materials_clearcoat (extensionsUsed only) |
| `glb_content.gltf` | minimal as a binary glTF (.glb bytes) under a .gltf name |
| `camera_*.gltf` | minimal's camera made degenerate: yfov 0, yfov pi, znear 0, zfar below znear, zero scale, zero quaternion |
| `lights_invalid.gltf` | minimal plus lights with a negative intensity, a negative colour, an intensity of 1e39 (infinite as a float) and a negative range |
| `accessor_offset_overflow.gltf` | POSITION accessor with byteOffset 2^64 - 16 (wraps a naive bounds check) |
| `accessor_count_overflow.gltf` | POSITION accessor with count 2^62 (stride x count wraps) |
| `huge_index_count.gltf` | index accessor with count 4 000 000 000 |
| `node_dag.gltf` | 40 nodes, each listing the next twice as children: 2^40 instances of the plane |
| `node_dag_no_mesh.gltf` | the same DAG without a mesh at its leaves (the plane is a separate root) |
| `node_dag_light.gltf` | the same DAG with minimal's light at its leaves (2^40 light nodes) |
| `texture_16bit.gltf` (+ `rgb16.png`) | base colour texture is a 16-bit RGB PNG |
| `texture_20000x1.gltf` (+ `wide_20000x1.png`) | base colour texture 20000 x 1 (past llvmpipe's GL_MAX_TEXTURE_SIZE 16384) |
| `texture_40000x1.gltf` (+ `wide_40000x1.png`) | base colour texture 40000 x 1 (past the loader's 32768) |
| `texture_uri_directory.gltf` | the image uri is `.`, a directory |
| `buffer_uri_directory.gltf` | the buffer uri is `.`, a directory |
| `buffer_dev_null.gltf` | the buffer uri is `/dev/null` (reached through `../` from the file's folder) |
| `texture_transform.gltf` (+ `.bin`, `stripes.png`) | plane with KHR_texture_transform (offset, rotation, scale) on its textures |
| `emissive_texture.gltf` (+ `.bin`, `stripes.png`) | plane emitting through an emissiveTexture, with KHR_materials_emissive_strength 2 |

Any scene a reader brings, to the end (issue 30): what each must print and its exit code (1:
refused; 0: rendered, with the warning or note quoted). `tests/00_scene_input.cmake` holds them
to it. All are `minimal.gltf` changed in one way unless said.

| file | what it is | lightpass (exit code: message) |
| --- | --- | --- |
| `draco_compressed.gltf` | KHR_draco_mesh_compression as writers make it: accessors without bufferView, the extension required | 1: "requires the extension KHR_draco_mesh_compression, which lightpass does not support (a compressed mesh: export it uncompressed)" |
| `meshopt_compressed.glb` | EXT_meshopt_compression required, its fallback buffer without data | 1: "requires the extension EXT_meshopt_compression ..." |
| `indices_count_zero.gltf`, `no_vertices.gltf`, `strip_two_indices.gltf` | an index count of 0; every accessor of count 0 and no indices; a TRIANGLE_STRIP of 2 indices | 1: "the scene has no triangles to draw" |
| `position_all_zero.gltf`, `degenerate_triangles.gltf` (+ `.bin`) | POSITION without a bufferView (all zeros); triangles whose corners lie on a line or coincide | 1: "the scene has no triangles to draw (its 2 triangles all have zero area ...)" |
| `position_vec2.gltf`, `position_scalar.gltf` | the POSITION accessor's type is VEC2, SCALAR | 1: "mesh 'plane' primitive 0: POSITION (accessor 0) is VEC2; glTF requires VEC3" |
| `attribute_no_buffer_view.gltf`, `indices_no_buffer_view.gltf` | TEXCOORD_0 without a bufferView; a second primitive whose indices have none (glTF: zeros) | 0: the plane as in `minimal.gltf` |
| `camera_yfov_float_pi.gltf` | yfov 3.14159265: below pi as a double, pi as a float | 1: "yfov 3.14159265 is below pi, but rounds to pi as a float" |
| `camera_yfov_3_14159.gltf` | yfov 3.14159: legal, the scene a speck | 0: "yfov 3.14159 leaves the scene a speck in the middle of the image; using 2.8" |
| `camera_znear_tiny.gltf` | znear 1e-30: legal, no depth precision | 0: "znear 1e-30 beside zfar 50 leaves the depth buffer no precision ...; using znear ..., zfar ..." |
| `extent_1e19.gltf`, `extent_1e-19.gltf` | the plane alone (no camera, no light) scaled by 1e19, 1e-19 | 0: "extent_1e19.gltf is 2.82843e+19 m across, where float lighting overflows: drawn scaled by 2^-64 ...", then the same image as `offset_0.gltf` |
| `offset_0.gltf`, `offset_1e6.gltf`, `offset_5e6.gltf`, `offset_1e7.gltf` | the plane alone at the origin, 1e6, 5e6, 1e7 m along x | 0: the others "lie ... m from the origin ...: moved by (...) to centre it", then the same image as `offset_0` |
| `back_faces_only.gltf` | the plane alone turned to face down, away from the automatic view | 0: "every face ... faces away from the automatic view's usual side ...: looking from the other side" |
| `light_range_tiny.gltf` | the light's range is 1e-30 | 0: "light 'light' is left out: its range 1e-30 m is a millionth of the scene's size ..." and "none of the scene's 1 lights can be used ...: using a default rig" |
| `only_light_left_out.gltf` | the only light has intensity -1 | 0: "light 'light' is left out ..." and "none of the scene's 1 lights can be used ...: using a default rig" |
| `material_huge_base_color.gltf`, `material_huge_specular.gltf` | baseColorFactor 3e38; specularColorFactor 1e36 | 0: "material 'grey': baseColorFactor (3e+38, ...) reflects more than all the light: clamped to 1" |
| `lights_100000.gltf` | 100 000 unbounded point lights from five nodes that list the next ten times | 1: "its 100000 lights reach 1e+05 times the whole scene ...: more work a frame than the loader accepts (4096)" |
| `buffer_dev_zero.gltf` | the buffer uri is the absolute path `/dev/zero` | 1: "cannot read '/dev/zero': not a regular file" |
| `image_huge_header.gltf` (+ `huge_header.png`) | a PNG whose header says 100000 x 100000 | 0: "texture 'huge_header.png' could not be loaded (it is 100000x100000, more than the loader accepts ..." |
| `image_shared_16.gltf` | 16 images naming `stripes.png` | 0: no warning (decoded and counted once) |
| `glb_bad_json.glb` | a .glb whose JSON chunk holds terminal control bytes | 1: tinygltf's parse error, those bytes shown as `\xNN` |
| `bad_lights.gltf` | minimal's plane with one good light and four defective ones (zero and negative intensity, negative range, a spot whose outer cone angle, 109°, is more than a hemisphere) | chapter 03's test: each defect named, the image still drawn |
)md";

void write_real_model_cases(const fs::path& dir) {
  {
    GltfBuilder b("no_camera_no_lights");
    b.add_mesh_node("box", b.add_mesh("box", make_box(glm::vec3(1.0f)), b.add_material(plain("grey"))), glm::vec3(0.0f));
    b.write(dir);
  }
  {
    // A reader's model as it often comes: an object standing on a floor, no camera, no lights
    // (the default rig's shadow, issue 29). The box is red so that a test tells it from the
    // mid-grey floor.
    GltfBuilder b("box_on_floor");
    Material floor = plain("floor"), box = plain("red");
    floor.base_color = {0.6f, 0.6f, 0.6f, 1.0f};
    box.base_color = {0.8f, 0.15f, 0.15f, 1.0f};
    b.add_mesh_node("floor", b.add_mesh("floor", make_rect(6.0f, 6.0f), b.add_material(floor)), glm::vec3(0.0f));
    b.add_mesh_node("box", b.add_mesh("box", make_box(glm::vec3(1.0f)), b.add_material(box)), glm::vec3(0.0f, 0.5f, 0.0f));
    b.write(dir);
  }
  {
    GltfBuilder b("indexed_nonormals");
    b.add_camera("view", {2.0f, 2.0f, 3.0f}, {0.0f, 0.0f, 0.0f}, 0.8f, 0.05f, 50.0f);
    b.add_point_light("light", {1.5f, 2.5f, 2.0f}, {1.0f, 1.0f, 1.0f}, 3.0f);
    b.add_mesh_node("cube", b.add_mesh("cube", shared_corner_cube(), -1), glm::vec3(0.0f));
    b.write(dir);
  }
  {
    // Both quads lie in y = 0, facing +Y, counter-clockwise seen from above.
    GltfBuilder b("strip_fan");
    b.add_camera("view", {1.25f, 3.0f, 0.5f}, {1.25f, 0.0f, 0.5f}, 0.8f, 0.05f, 50.0f, {0.0f, 0.0f, -1.0f});
    b.add_point_light("light", {1.25f, 2.0f, 0.5f}, {1.0f, 1.0f, 1.0f}, 4.0f);
    Mesh strip, fan;
    strip.positions = {{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {1, 0, 1}};
    fan.positions = {{2, 0, 0.5f}, {1.5f, 0, 0}, {1.5f, 0, 1}, {2.5f, 0, 1}, {2.5f, 0, 0}, {1.5f, 0, 0}};
    int m = b.add_material(plain("grey"));
    b.add_mesh_node("strip", b.add_mesh("strip", strip, m), glm::vec3(0.0f));
    b.add_mesh_node("fan", b.add_mesh("fan", fan, m), glm::vec3(0.0f));
    json doc = b.document();
    doc["meshes"][0]["primitives"][0]["mode"] = 5;
    doc["meshes"][1]["primitives"][0]["mode"] = 6;
    write_doc(dir, "strip_fan", doc);
    write_bytes(dir / "strip_fan.bin", b.binary());
  }
  {
    GltfBuilder b("points_only");
    plane_scene(b, make_rect(2.0f, 2.0f), b.add_material(plain("grey")), true);
    json doc = b.document();
    doc["meshes"][0]["primitives"][0]["mode"] = 0;
    doc["meshes"][0]["primitives"][0].erase("indices");
    write_doc(dir, "points_only", doc);
    write_bytes(dir / "points_only.bin", b.binary());
  }
  {
    json doc = minimal_doc();
    json lines = doc["meshes"][0]["primitives"][0];
    lines["mode"] = 1;
    doc["meshes"][0]["primitives"].push_back(lines);
    write_doc(dir, "lines_and_triangles", doc);
  }
  for (const char* ext : {"KHR_draco_mesh_compression", "EXT_meshopt_compression"}) {
    json doc = minimal_doc();
    add_extension(doc, ext, true);
    write_doc(dir, std::string("requires_") + (ext[0] == 'K' ? "draco" : "meshopt"), doc);
  }
  {
    json doc = minimal_doc();
    add_extension(doc, "KHR_materials_clearcoat", false);
    doc["materials"][0]["extensions"]["KHR_materials_clearcoat"] = {{"clearcoatFactor", 1.0}};
    write_doc(dir, "uses_clearcoat", doc);
  }
  {
    GltfBuilder b("minimal");
    plane_scene(b, make_rect(2.0f, 2.0f), b.add_material(plain("grey")), true);
    write_bytes(dir / "glb_content.gltf", glb(b.document(), b.binary()));
  }
  // Textured planes: stripes.png is 8 x 8, the left half white, the right half black.
  {
    std::vector<uint8_t> rgb(8 * 8 * 3);
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x)
        for (int c = 0; c < 3; ++c) rgb[size_t((y * 8 + x) * 3 + c)] = x < 4 ? 255 : 0;
    write_png_rgb(dir / "stripes.png", 8, 8, rgb);
  }
  {
    GltfBuilder b("texture_transform");
    Material m = plain("transformed");
    m.base_color_texture = b.add_texture("stripes.png");
    m.normal_texture = b.add_texture("stripes.png");
    plane_scene(b, make_rect(2.0f, 2.0f), b.add_material(m), true);
    json doc = b.document();
    const json transform = {{"offset", {0.5, 0.25}}, {"rotation", 1.5707963267948966}, {"scale", {2.0, 3.0}}};
    doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"]["KHR_texture_transform"] = transform;
    doc["materials"][0]["normalTexture"]["extensions"]["KHR_texture_transform"] = transform;
    add_extension(doc, "KHR_texture_transform", true);
    write_doc(dir, "texture_transform", doc);
    write_bytes(dir / "texture_transform.bin", b.binary());
  }
  {
    GltfBuilder b("emissive_texture");
    Material m = plain("label");
    m.base_color = {0.05f, 0.05f, 0.05f, 1.0f};
    m.emissive = {1.0f, 0.5f, 0.25f};
    plane_scene(b, make_rect(2.0f, 2.0f), b.add_material(m), true);
    int texture = b.add_texture("stripes.png");
    json doc = b.document();
    doc["materials"][0]["emissiveTexture"] = {{"index", texture}};
    doc["materials"][0]["extensions"]["KHR_materials_emissive_strength"] = {{"emissiveStrength", 2.0}};
    add_extension(doc, "KHR_materials_emissive_strength", false);
    write_doc(dir, "emissive_texture", doc);
    write_bytes(dir / "emissive_texture.bin", b.binary());
  }
}

void write_hostile_cases(const fs::path& dir) {
  const std::pair<const char*, std::function<void(json&)>> cameras[] = {
      {"camera_yfov_zero", [](json& d) { d["cameras"][0]["perspective"]["yfov"] = 0; }},
      {"camera_yfov_pi", [](json& d) { d["cameras"][0]["perspective"]["yfov"] = 3.1415927; }},
      {"camera_znear_zero", [](json& d) { d["cameras"][0]["perspective"]["znear"] = 0; }},
      {"camera_zfar_below_znear", [](json& d) { d["cameras"][0]["perspective"]["zfar"] = 0.01; }},
      {"camera_zero_scale", [](json& d) { camera_node(d)["scale"] = {0.0, 0.0, 0.0}; }},
      {"camera_zero_quaternion", [](json& d) { camera_node(d)["rotation"] = {0.0, 0.0, 0.0, 0.0}; }},
  };
  for (const auto& [name, damage] : cameras) {
    json doc = minimal_doc();
    damage(doc);
    write_doc(dir, name, doc);
  }
  {
    // JSON has no infinity: 1e39 is a double that overflows the float the loader keeps.
    json doc = minimal_doc();
    auto add_light = [&](const std::string& name, const json& light, float x) {
      json l = light;
      l["name"] = name;
      l["type"] = "point";
      doc["extensions"]["KHR_lights_punctual"]["lights"].push_back(l);
      int index = int(doc["extensions"]["KHR_lights_punctual"]["lights"].size()) - 1;
      doc["nodes"].push_back({{"name", name}, {"translation", {x, 1.0, 0.0}}, {"extensions", {{"KHR_lights_punctual", {{"light", index}}}}}});
      doc["scenes"][0]["nodes"].push_back(doc["nodes"].size() - 1);
    };
    add_light("negative_intensity", {{"intensity", -5.0}}, -1.0f);
    add_light("negative_colour", {{"intensity", 2.0}, {"color", {1.0, -1.0, 1.0}}}, -0.5f);
    add_light("infinite_intensity", {{"intensity", 12345.678}}, 0.5f);
    add_light("negative_range", {{"intensity", 2.0}, {"range", -3.0}}, 1.0f);
    std::string text = format_json(doc);
    text.replace(text.find("12345.678"), 9, "1e39");
    write_text(dir / "lights_invalid.gltf", text);
  }
  {
    json doc = minimal_doc();
    int pos = doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"];
    doc["accessors"][size_t(pos)]["byteOffset"] = uint64_t(0) - 16;  // 2^64 - 16
    write_doc(dir, "accessor_offset_overflow", doc);
  }
  {
    json doc = minimal_doc();
    int pos = doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"];
    doc["accessors"][size_t(pos)]["count"] = uint64_t(1) << 62;
    write_doc(dir, "accessor_count_overflow", doc);
  }
  {
    json doc = minimal_doc();
    int idx = doc["meshes"][0]["primitives"][0]["indices"];
    doc["accessors"][size_t(idx)]["count"] = 4000000000ull;
    write_doc(dir, "huge_index_count", doc);
  }
  for (const char* leaf_has : {"mesh", "nothing", "light"}) {
    json doc = minimal_doc();
    json plane;
    for (auto& n : doc["nodes"])
      if (n.contains("mesh")) plane = n;
    const size_t first = doc["nodes"].size();
    for (size_t i = 0; i < 40; ++i) doc["nodes"].push_back({{"name", "dag" + std::to_string(i)}, {"children", {first + i + 1, first + i + 1}}});
    json leaf = {{"name", "leaf"}};
    const std::string what = leaf_has;
    if (what == "mesh") leaf["mesh"] = plane["mesh"];
    if (what == "light") leaf["extensions"] = {{"KHR_lights_punctual", {{"light", 0}}}};
    doc["nodes"].push_back(leaf);
    doc["scenes"][0]["nodes"].push_back(first);
    write_doc(dir, what == "mesh" ? "node_dag" : what == "light" ? "node_dag_light" : "node_dag_no_mesh", doc);
  }
  {
    write_bytes(dir / "rgb16.png", png16(4, 4));
    for (int width : {20000, 40000}) {
      std::vector<uint8_t> rgb(size_t(width) * 3, 200);
      std::string png = "wide_" + std::to_string(width) + "x1.png";
      write_png_rgb(dir / png, width, 1, rgb);
    }
    for (const char* image : {"rgb16.png", "wide_20000x1.png", "wide_40000x1.png", "."}) {
      json doc = minimal_doc();
      doc["images"] = json::array({{{"uri", image}}});
      doc["textures"] = json::array({{{"source", 0}}});
      doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
      std::string name = image == std::string("rgb16.png") ? "texture_16bit"
                         : image == std::string(".")       ? "texture_uri_directory"
                                                           : "texture_" + std::string(image).substr(5, std::strlen(image) - 9);
      write_doc(dir, name, doc);
    }
  }
  // tinygltf looks for a uri under the file's folder: enough "../" reach / from any depth.
  for (const char* uri : {".", "../../../../../../../../../../../../../../../../dev/null"}) {
    json doc = minimal_doc();
    doc["buffers"][0]["uri"] = uri;
    write_doc(dir, std::string(uri) == "." ? "buffer_uri_directory" : "buffer_dev_null", doc);
  }
}

// Issue 30: any scene a reader brings, to the end. Each file is minimal.gltf (or a plane of
// its own) changed in one way; tests/00_scene_input.cmake says what each must print.
void write_any_scene_cases(const fs::path& dir) {
  auto variant = [&](const std::string& name, const std::function<void(json&)>& change) {
    json doc = minimal_doc();
    change(doc);
    write_doc(dir, name, doc);
  };
  auto prim = [](json& d) -> json& { return d["meshes"][0]["primitives"][0]; };
  // Compressed meshes as their writers make them: Draco's accessors have no bufferView (the
  // data is in the extension's), meshopt's fallback buffer has no data.
  variant("draco_compressed", [&](json& d) {
    for (auto& a : d["accessors"]) a.erase("bufferView");
    prim(d)["extensions"]["KHR_draco_mesh_compression"] = {
        {"bufferView", 0}, {"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}, {"TANGENT", 3}}}};
    add_extension(d, "KHR_draco_mesh_compression", true);
  });
  {
    json d = minimal_doc();
    d["buffers"].push_back({{"byteLength", 1 << 20}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}});
    for (auto& v : d["bufferViews"]) {
      v["extensions"]["EXT_meshopt_compression"] = {{"buffer", 0}, {"byteOffset", v["byteOffset"]}, {"byteLength", v["byteLength"]},
                                                    {"byteStride", 4}, {"count", 1}, {"mode", "ATTRIBUTES"}};
      v["buffer"] = 1;
    }
    add_extension(d, "EXT_meshopt_compression", true);
    GltfBuilder b("minimal");
    plane_scene(b, make_rect(2.0f, 2.0f), b.add_material(plain("grey")), true);
    write_bytes(dir / "meshopt_compressed.glb", glb(d, b.binary()));
  }
  // Nothing to draw: no indices, no vertices, a strip of two indices; POSITION of a type that is
  // not VEC3; every POSITION zero (an accessor without a bufferView); only degenerate triangles.
  variant("indices_count_zero", [&](json& d) { d["accessors"][int(prim(d)["indices"])]["count"] = 0; });
  variant("no_vertices", [&](json& d) {
    for (auto& a : d["accessors"]) a["count"] = 0;
    prim(d).erase("indices");
  });
  variant("strip_two_indices", [&](json& d) {
    prim(d)["mode"] = 5;
    d["accessors"][int(prim(d)["indices"])]["count"] = 2;
  });
  variant("position_vec2", [&](json& d) { d["accessors"][0]["type"] = "VEC2"; });
  variant("position_scalar", [&](json& d) { d["accessors"][0]["type"] = "SCALAR"; });
  variant("position_all_zero", [&](json& d) {
    d["accessors"][0].erase("bufferView");
    d["accessors"][0]["min"] = {0.0, 0.0, 0.0};
    d["accessors"][0]["max"] = {0.0, 0.0, 0.0};
  });
  {
    GltfBuilder b("degenerate_triangles");
    Mesh line;
    line.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {0, 1, 0}, {0, 2, 0}};
    b.add_camera("view", {0.0f, 1.0f, 4.0f}, {0.0f, 1.0f, 0.0f}, 0.8f, 0.05f, 50.0f);
    b.add_point_light("light", {0.0f, 2.0f, 2.0f}, {1.0f, 1.0f, 1.0f}, 2.0f);
    b.add_mesh_node("lines", b.add_mesh("lines", line, b.add_material(plain("grey"))), glm::vec3(0.0f));
    b.write(dir);
  }
  // Accessors without a bufferView are zeros (glTF 2.0 §3.6.2.1): TEXCOORD_0 here, and the
  // indices of a second primitive (all 0: a triangle of no area beside minimal's plane).
  variant("attribute_no_buffer_view", [&](json& d) { d["accessors"][int(prim(d)["attributes"]["TEXCOORD_0"])].erase("bufferView"); });
  variant("indices_no_buffer_view", [&](json& d) {
    json zero = d["accessors"][int(prim(d)["indices"])];
    zero.erase("bufferView");
    d["accessors"].push_back(zero);
    json second = prim(d);
    second["indices"] = d["accessors"].size() - 1;
    d["meshes"][0]["primitives"].push_back(second);
  });
  // Cameras: a yfov that is below pi as a double and pi as a float; legal ones that leave no image.
  variant("camera_yfov_float_pi", [&](json& d) { d["cameras"][0]["perspective"]["yfov"] = 3.14159265; });
  variant("camera_yfov_3_14159", [&](json& d) { d["cameras"][0]["perspective"]["yfov"] = 3.14159; });
  variant("camera_znear_tiny", [&](json& d) { d["cameras"][0]["perspective"]["znear"] = 1e-30; });
  // The automatic view of extreme sizes and places: minimal's plane alone (no camera, no light),
  // scaled or moved.
  const std::pair<const char*, std::function<void(json&)>> placed[] = {
      {"extent_1e19", [](json& n) { n["scale"] = {1e19, 1e19, 1e19}; }},
      {"extent_1e-19", [](json& n) { n["scale"] = {1e-19, 1e-19, 1e-19}; }},
      {"offset_0", [](json&) {}},  // the control: the same plane at the origin
      {"offset_1e7", [](json& n) { n["translation"] = {1e7, 0.0, 0.0}; }},
      {"offset_5e6", [](json& n) { n["translation"] = {5e6, 0.0, 0.0}; }},
      {"offset_1e6", [](json& n) { n["translation"] = {1e6, 0.0, 0.0}; }},
      // Rotated half a turn about X: the plane faces down, away from a view from above.
      {"back_faces_only", [](json& n) { n["rotation"] = {1.0, 0.0, 0.0, 0.0}; }}};
  for (const auto& [name, place] : placed)
    variant(name, [&](json& d) {
      place(d["nodes"][2]);
      d["scenes"][0]["nodes"] = {2};
    });
  // Lights: one of a range too small to light anything; a scene whose only light is left out.
  variant("light_range_tiny", [&](json& d) { d["extensions"]["KHR_lights_punctual"]["lights"][0]["range"] = 1e-30; });
  variant("only_light_left_out", [&](json& d) { d["extensions"]["KHR_lights_punctual"]["lights"][0]["intensity"] = -1.0; });
  // Material factors that are finite floats and break the lighting's arithmetic.
  variant("material_huge_base_color", [&](json& d) {
    d["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {3e38, 3e38, 3e38, 1.0};
  });
  variant("material_huge_specular", [&](json& d) {
    d["materials"][0]["extensions"]["KHR_materials_specular"]["specularColorFactor"] = {1e36, 1e36, 1e36};
  });
  // 100 000 unbounded point lights from a small file: five levels of nodes listing the next ten times.
  variant("lights_100000", [&](json& d) {
    const size_t first = d["nodes"].size();
    for (size_t i = 0; i < 5; ++i) d["nodes"].push_back({{"name", "x10_" + std::to_string(i)}, {"children", json::array()}});
    for (size_t i = 0; i < 5; ++i)
      for (int k = 0; k < 10; ++k) d["nodes"][first + i]["children"].push_back(first + i + 1);
    d["nodes"].push_back({{"name", "bulb"}, {"translation", {0.0, 1.0, 0.0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    d["scenes"][0]["nodes"] = {0, 2, first};
  });
  // Chapter 03's defective lights: one good light and four that the light set must leave out
  // or warn about, each named in the messages.
  variant("bad_lights", [&](json& d) {
    json lights = json::array();
    auto add = [&](const char* name, const char* type, std::vector<double> colour, double intensity) {
      lights.push_back({{"name", name}, {"type", type}, {"color", colour}, {"intensity", intensity}});
      return lights.size() - 1;
    };
    lights[add("good", "point", {1, 0.9, 0.8}, 2.0)]["range"] = 3.0;
    add("dark", "point", {1, 1, 1}, 0.0);
    add("negative", "point", {1, 1, 1}, -2.0);
    lights[add("negative_range", "point", {0.4, 0.6, 1}, 0.3)]["range"] = -3.0;
    const size_t spot = add("wide_spot", "spot", {1, 0.5, 0.2}, 1.5);
    lights[spot]["range"] = 4.0;
    lights[spot]["spot"] = {{"innerConeAngle", 0.5}, {"outerConeAngle", 1.9}};
    d["extensions"]["KHR_lights_punctual"]["lights"] = lights;
    json camera = d["nodes"][0], plane = d["nodes"][2];
    d["nodes"] = {camera, plane};
    const std::pair<const char*, std::vector<double>> at[] = {
        {"good", {0.5, 1.0, 0.0}}, {"dark", {0, 1.5, 0}}, {"negative", {0, 1.5, 0}}, {"negative_range", {-0.6, 0.8, 0.3}},
        {"wide_spot", {0.0, 1.2, -0.5}}};
    for (size_t i = 0; i < std::size(at); ++i) {
      json n = {{"name", at[i].first}, {"translation", at[i].second}, {"extensions", {{"KHR_lights_punctual", {{"light", i}}}}}};
      if (i == 4) n["rotation"] = {-0.70710678, 0, 0, 0.70710678};  // the spot looks down
      d["nodes"].push_back(n);
    }
    d["scenes"][0]["nodes"] = {0, 1, 2, 3, 4, 5, 6};
  });
  // Files and messages.
  variant("buffer_dev_zero", [&](json& d) { d["buffers"][0]["uri"] = "/dev/zero"; });
  {
    // A PNG header that claims 100000 x 100000 and has no pixel data.
    std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    auto crc32 = [](const std::vector<uint8_t>& p) {
      uint32_t c = 0xFFFFFFFFu;
      for (uint8_t v : p) {
        c ^= v;
        for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
      }
      return ~c;
    };
    auto chunk = [&](const char* type, std::vector<uint8_t> data) {
      for (int i = 3; i >= 0; --i) png.push_back(uint8_t(data.size() >> (8 * i)));
      std::vector<uint8_t> td(type, type + 4);
      td.insert(td.end(), data.begin(), data.end());
      png.insert(png.end(), td.begin(), td.end());
      uint32_t c = crc32(td);
      for (int i = 3; i >= 0; --i) png.push_back(uint8_t(c >> (8 * i)));
    };
    std::vector<uint8_t> ihdr;
    for (uint32_t v : {100000u, 100000u})
      for (int i = 3; i >= 0; --i) ihdr.push_back(uint8_t(v >> (8 * i)));
    ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0});
    chunk("IHDR", ihdr);
    chunk("IEND", {});
    write_bytes(dir / "huge_header.png", png);
    variant("image_huge_header", [&](json& d) {
      d["images"] = json::array({{{"uri", "huge_header.png"}}});
      d["textures"] = json::array({{{"source", 0}}});
      d["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
    });
  }
  // One image file named by 16 images: decoded and counted once.
  variant("image_shared_16", [&](json& d) {
    d["images"] = json::array();
    d["textures"] = json::array();
    for (int i = 0; i < 16; ++i) {
      d["images"].push_back({{"uri", "stripes.png"}});
      d["textures"].push_back({{"source", i}});
    }
    d["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 15}};
  });
  {
    // A .glb whose JSON chunk is not JSON and holds bytes no terminal should be sent.
    std::vector<uint8_t> out = {'g', 'l', 'T', 'F', 2, 0, 0, 0, 36, 0, 0, 0, 16, 0, 0, 0, 'J', 'S', 'O', 'N',
                                '{', '"', 0x9B, '2', 'J', 0xFF, 0x1B, 0x07, 0x00, 'x', 0x01, 0x02, 0x03, '}', ' ', ' '};
    write_bytes(dir / "glb_bad_json.glb", out);
  }
}

}  // namespace

void write_test_data(const fs::path& dir) {
  fs::create_directories(dir);
  write_text(dir / "README.md", kReadme);
  write_text(dir / "empty_file.gltf", "");

  {
    GltfBuilder b("minimal");
    plane_scene(b, make_rect(2.0f, 2.0f), b.add_material(plain("grey")), true);
    b.write(dir);
    const std::string text = format_json(b.document());
    write_text(dir / "malformed.gltf", text.substr(0, text.size() / 2));
  }
  {
    GltfBuilder b("missing_buffer");
    plane_scene(b, make_rect(2.0f, 2.0f), b.add_material(plain("grey")), true);
    write_text(dir / "missing_buffer.gltf", format_json(b.document()));  // no .bin written
  }
  {
    GltfBuilder b("missing_texture");
    Material m = plain("textured");
    m.base_color_texture = b.add_texture("missing_texture.png");  // never written
    plane_scene(b, make_rect(2.0f, 2.0f), b.add_material(m), true);
    b.write(dir);
  }
  {
    GltfBuilder b("nonindexed_nonormals");
    b.add_camera("view", {2.0f, 2.0f, 3.0f}, {0.0f, 0.0f, 0.0f}, 0.8f, 0.05f, 50.0f);
    b.add_point_light("light", {1.5f, 2.5f, 2.0f}, {1.0f, 1.0f, 1.0f}, 3.0f);
    const Mesh box = make_box(glm::vec3(1.0f));
    Mesh soup;
    for (uint32_t i : box.indices) soup.positions.push_back(box.positions[i]);
    b.add_mesh_node("cube", b.add_mesh("cube", soup, -1), glm::vec3(0.0f));
    b.write(dir);
  }
  {
    GltfBuilder b("no_camera");
    plane_scene(b, make_rect(2.0f, 2.0f), b.add_material(plain("grey")), false);
    b.write(dir);
  }
  {
    GltfBuilder b("bad_index");
    Mesh plane = make_rect(2.0f, 2.0f);
    plane.indices.back() = 99;  // 4 vertices
    plane_scene(b, plane, b.add_material(plain("grey")), true);
    b.write(dir);
  }
  write_real_model_cases(dir);
  write_hostile_cases(dir);
  write_any_scene_cases(dir);
}

}  // namespace scenegen
