// scenegen --verify: loads the generated files with tinygltf (the loader the book uses) and
// checks them against the lightpass conventions, then prints what each scene holds and the
// irradiance its lights give on the analytic shapes (the exposure check).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <tiny_gltf.h>

#include "mesh.h"
#include "scenes.h"

namespace scenegen {

namespace fs = std::filesystem;

namespace {

struct Report {
  std::vector<std::string> problems;
  void fail(const std::string& what) { problems.push_back(what); }
};

bool load(const fs::path& path, tinygltf::Model& model, std::string& err, std::string& warn) {
  tinygltf::TinyGLTF loader;
  return loader.LoadASCIIFromFile(&model, &err, &warn, path.string());
}

// Reads an accessor as up to 4 floats (or integers) per element; checks it lies in its view.
bool read_accessor(const tinygltf::Model& m, int index, std::vector<glm::dvec4>& out, Report& r, const std::string& what) {
  if (index < 0 || index >= static_cast<int>(m.accessors.size())) {
    r.fail(what + ": accessor index out of range");
    return false;
  }
  const auto& a = m.accessors[index];
  if (a.bufferView < 0 || a.bufferView >= static_cast<int>(m.bufferViews.size())) {
    r.fail(what + ": accessor without a valid bufferView");
    return false;
  }
  const auto& v = m.bufferViews[a.bufferView];
  const auto& buf = m.buffers.at(v.buffer);
  const int comps = tinygltf::GetNumComponentsInType(a.type);
  const int csize = tinygltf::GetComponentSizeInBytes(a.componentType);
  if (comps < 1 || comps > 4 || csize < 1) {
    r.fail(what + ": unsupported accessor type");
    return false;
  }
  const size_t elem = static_cast<size_t>(comps * csize);
  const size_t stride = v.byteStride ? v.byteStride : elem;
  if (v.byteOffset + v.byteLength > buf.data.size() ||
      (a.count > 0 && a.byteOffset + stride * (a.count - 1) + elem > v.byteLength)) {
    r.fail(what + ": accessor runs past its bufferView / buffer");
    return false;
  }
  out.assign(a.count, glm::dvec4(0.0));
  const uint8_t* base = buf.data.data() + v.byteOffset + a.byteOffset;
  for (size_t i = 0; i < a.count; ++i)
    for (int c = 0; c < comps; ++c) {
      const uint8_t* p = base + i * stride + static_cast<size_t>(c * csize);
      double x = 0;
      switch (a.componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: { float f; std::memcpy(&f, p, 4); x = f; break; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { uint32_t u; std::memcpy(&u, p, 4); x = u; break; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { uint16_t u; std::memcpy(&u, p, 2); x = u; break; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: x = *p; break;
        default: r.fail(what + ": unexpected component type"); return false;
      }
      out[i][c] = x;
    }
  return true;
}

glm::dmat4 node_matrix(const tinygltf::Node& n) {
  if (n.matrix.size() == 16) {
    glm::dmat4 m;
    for (int i = 0; i < 16; ++i) m[i / 4][i % 4] = n.matrix[i];
    return m;
  }
  glm::dmat4 t(1.0), r(1.0), s(1.0);
  if (n.translation.size() == 3) t[3] = glm::dvec4(n.translation[0], n.translation[1], n.translation[2], 1.0);
  if (n.rotation.size() == 4) r = glm::mat4_cast(glm::dquat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]));
  if (n.scale.size() == 3) s = glm::scale(glm::dmat4(1.0), glm::dvec3(n.scale[0], n.scale[1], n.scale[2]));
  return t * r * s;
}

const tinygltf::Value* lightpass_extras(const tinygltf::Value& extras) {
  if (!extras.IsObject() || !extras.Has("lightpass")) return nullptr;
  return &extras.Get("lightpass");
}

struct ShapeProbe {
  std::string node;
  std::vector<glm::dvec3> points, normals;
};

struct LightInfo {
  std::string type;
  glm::dvec3 color, pos, dir;
  double intensity, range, inner, outer;
};

// Irradiance (per channel) from all lights at a point, as the chapters 1-4 renderers compute it
// (inverse square with the glTF range window, smooth spot cone; no shadows).
glm::dvec3 irradiance(const std::vector<LightInfo>& lights, const glm::dvec3& p, const glm::dvec3& n) {
  glm::dvec3 e(0.0);
  for (const auto& l : lights) {
    if (l.type == "directional") {
      e += l.color * l.intensity * std::max(0.0, glm::dot(n, -l.dir));
      continue;
    }
    const glm::dvec3 d = l.pos - p;
    const double dist2 = std::max(glm::dot(d, d), 1e-8), dist = std::sqrt(dist2);
    const glm::dvec3 L = d / dist;
    double att = 1.0 / dist2;
    if (l.range > 0.0) {
      const double q = dist / l.range;
      att *= std::pow(std::clamp(1.0 - q * q * q * q, 0.0, 1.0), 2.0);
    }
    if (l.type == "spot") {
      const double cos_outer = std::cos(l.outer), cos_inner = std::cos(l.inner);
      const double scale = 1.0 / std::max(1e-3, cos_inner - cos_outer);
      const double t = std::clamp(glm::dot(l.dir, -L) * scale - cos_outer * scale, 0.0, 1.0);
      att *= t * t;
    }
    e += l.color * l.intensity * att * std::max(0.0, glm::dot(n, L));
  }
  return e;
}

// Checks one loaded model; `scene_rules` adds the rules the book's scenes follow beyond a
// valid glTF (cameras present, every material with a name and KHR_materials_specular, ...).
void check_model(const tinygltf::Model& m, bool scene_rules, Report& r, bool print_summary, const std::string& label) {
  if (m.asset.version != "2.0") r.fail("asset.version is not 2.0");
  const std::set<std::string> used(m.extensionsUsed.begin(), m.extensionsUsed.end());
  if (!m.lights.empty() && !used.count("KHR_lights_punctual")) r.fail("lights but KHR_lights_punctual not in extensionsUsed");
  if (!m.materials.empty() && !used.count("KHR_materials_specular")) r.fail("KHR_materials_specular not in extensionsUsed");
  if (m.scenes.empty() || m.defaultScene < 0) {
    r.fail("no default scene");
    return;
  }
  const auto& scene = m.scenes[m.defaultScene];
  if (scene.nodes.size() != m.nodes.size()) r.fail("not every node is a root of the scene");
  if (const auto* lp = lightpass_extras(scene.extras); !lp || !lp->Has("ambient") || lp->Get("ambient").ArrayLen() != 3)
    r.fail("scene extras.lightpass.ambient [r,g,b] missing");

  // Nodes, names, cameras, lights.
  std::set<std::string> names;
  std::vector<std::string> camera_names;
  std::vector<int> light_refs(m.lights.size(), 0);
  std::vector<LightInfo> lights;
  std::vector<ShapeProbe> probes;
  int first_camera_node = -1;
  for (size_t i = 0; i < m.nodes.size(); ++i) {
    const auto& n = m.nodes[i];
    if (n.name.empty()) r.fail("node " + std::to_string(i) + " has no name");
    else if (!names.insert(n.name).second) r.fail("node name '" + n.name + "' is not unique");
    if (!n.children.empty()) r.fail("node '" + n.name + "' has children (scenes are flat)");
    const glm::dmat4 world = node_matrix(n);
    if (n.camera >= 0) {
      if (first_camera_node < 0) first_camera_node = static_cast<int>(i);
      const auto& c = m.cameras.at(n.camera);
      camera_names.push_back(n.name);
      if (c.type != "perspective") r.fail("camera '" + n.name + "' is not perspective");
      if (c.name != n.name) r.fail("camera '" + c.name + "' and its node '" + n.name + "' differ in name");
      if (std::fabs(c.perspective.aspectRatio - 16.0 / 9.0) > 1e-6) r.fail("camera '" + n.name + "' aspect is not 16:9");
      if (!(c.perspective.yfov > 0.0 && c.perspective.yfov < 3.0)) r.fail("camera '" + n.name + "' yfov out of range");
      if (!(c.perspective.znear > 0.0 && c.perspective.zfar > c.perspective.znear)) r.fail("camera '" + n.name + "' bad clip planes");
    }
    if (auto it = n.extensions.find("KHR_lights_punctual"); it != n.extensions.end()) {
      const int li = it->second.Get("light").GetNumberAsInt();
      if (li < 0 || li >= static_cast<int>(m.lights.size())) {
        r.fail("node '" + n.name + "' refers to a missing light");
      } else {
        ++light_refs[li];
        const auto& l = m.lights[li];
        LightInfo info;
        info.type = l.type;
        info.color = l.color.size() == 3 ? glm::dvec3(l.color[0], l.color[1], l.color[2]) : glm::dvec3(1.0);
        info.pos = glm::dvec3(world[3]);
        info.dir = glm::normalize(glm::dvec3(world * glm::dvec4(0, 0, -1, 0)));
        info.intensity = l.intensity;
        info.range = l.range;
        info.inner = l.spot.innerConeAngle;
        info.outer = l.spot.outerConeAngle;
        lights.push_back(info);
        if (l.name != n.name) r.fail("light '" + l.name + "' and its node '" + n.name + "' differ in name");
        if (l.type != "point" && l.type != "spot" && l.type != "directional") r.fail("light '" + l.name + "' bad type");
        if (!(l.intensity > 0.0)) r.fail("light '" + l.name + "' intensity <= 0");
        if (l.color.size() != 3) r.fail("light '" + l.name + "' colour is not [r,g,b]");
        if (l.type == "spot" && !(l.spot.innerConeAngle >= 0.0 && l.spot.innerConeAngle < l.spot.outerConeAngle &&
                                  l.spot.outerConeAngle <= 1.5707964))
          r.fail("light '" + l.name + "' bad cone angles");
      }
    }
    if (const auto* lp = lightpass_extras(n.extras); lp && lp->Has("shape")) {
      const std::string shape = lp->Get("shape").Get<std::string>();
      if (n.mesh < 0) r.fail("shape node '" + n.name + "' has no mesh");
      std::vector<glm::dvec4> pos;
      if (n.mesh >= 0) read_accessor(m, m.meshes[n.mesh].primitives.at(0).attributes.at("POSITION"), pos, r, n.name);
      ShapeProbe probe{n.name, {}, {}};
      if (shape == "sphere") {
        const double radius = lp->Get("radius").GetNumberAsDouble();
        if (!n.rotation.empty() || !n.scale.empty() || !n.matrix.empty()) r.fail("sphere '" + n.name + "' has rotation/scale");
        for (const auto& p : pos)
          if (std::fabs(glm::length(glm::dvec3(p)) - radius) > 1e-5 * radius) {
            r.fail("sphere '" + n.name + "' mesh is not of its radius");
            break;
          }
        const glm::dvec3 c(world[3]);
        for (int el = 0; el < 4; ++el)
          for (int az = 0; az < (el == 3 ? 1 : 8); ++az) {
            const double t = glm::radians(el * 30.0), p = glm::radians(az * 45.0);
            const glm::dvec3 nn(std::cos(t) * std::sin(p), std::sin(t), std::cos(t) * std::cos(p));
            probe.points.push_back(c + nn * radius);
            probe.normals.push_back(nn);
          }
      } else if (shape == "rect") {
        const double sx = lp->Get("size").Get(0).GetNumberAsDouble(), sz = lp->Get("size").Get(1).GetNumberAsDouble();
        if (!n.scale.empty() || !n.matrix.empty()) r.fail("rect '" + n.name + "' has scale/matrix");
        glm::dvec3 lo(1e30), hi(-1e30);
        for (const auto& p : pos) {
          lo = glm::min(lo, glm::dvec3(p));
          hi = glm::max(hi, glm::dvec3(p));
        }
        const double tol = 1e-5 * std::max(sx, sz);
        if (std::fabs(lo.x + sx / 2) > tol || std::fabs(hi.x - sx / 2) > tol || std::fabs(lo.z + sz / 2) > tol ||
            std::fabs(hi.z - sz / 2) > tol || std::fabs(lo.y) > tol || std::fabs(hi.y) > tol)
          r.fail("rect '" + n.name + "' mesh does not match its size");
        // About one sample per metre (3 .. 64 along each side).
        const int ga = std::clamp(static_cast<int>(std::lround(sx)), 3, 64);
        const int gb = std::clamp(static_cast<int>(std::lround(sz)), 3, 64);
        const glm::dvec3 nn = glm::normalize(glm::dvec3(world * glm::dvec4(0, 1, 0, 0)));
        for (int a = 0; a < ga; ++a)
          for (int b = 0; b < gb; ++b) {
            const glm::dvec4 local((a + 0.5) / ga * sx - sx / 2, 0.0, (b + 0.5) / gb * sz - sz / 2, 1.0);
            probe.points.push_back(glm::dvec3(world * local) + nn * 1e-4);
            probe.normals.push_back(nn);
          }
      } else {
        r.fail("node '" + n.name + "' has unknown shape '" + shape + "'");
      }
      if (!probe.points.empty()) probes.push_back(probe);
    }
  }
  for (size_t i = 0; i < light_refs.size(); ++i)
    if (light_refs[i] != 1) r.fail("light " + std::to_string(i) + " is used by " + std::to_string(light_refs[i]) + " nodes");

  if (scene_rules) {
    if (camera_names.empty()) r.fail("no camera");
    if (m.lights.empty()) r.fail("no light");
    for (const auto& mat : m.materials) {
      if (mat.name.empty()) r.fail("a material has no name");
      auto it = mat.extensions.find("KHR_materials_specular");
      if (it == mat.extensions.end() || !it->second.Has("specularColorFactor") || !it->second.Has("specularFactor"))
        r.fail("material '" + mat.name + "' lacks KHR_materials_specular factors");
      if (mat.pbrMetallicRoughness.metallicFactor != 0.0) r.fail("material '" + mat.name + "' is metallic");
    }
    for (const auto& img : m.images)
      if (img.image.empty()) r.fail("image '" + img.uri + "' did not load");
  }

  // Meshes.
  size_t vertices = 0, triangles = 0;
  for (const auto& mesh : m.meshes)
    for (const auto& prim : mesh.primitives) {
      const std::string what = "mesh '" + mesh.name + "'";
      if (prim.mode != TINYGLTF_MODE_TRIANGLES) r.fail(what + " is not a triangle list");
      auto attr = [&](const char* key) {
        auto it = prim.attributes.find(key);
        return it == prim.attributes.end() ? -1 : it->second;
      };
      std::vector<glm::dvec4> pos, nrm, uv, tan, idx;
      if (attr("POSITION") < 0 || !read_accessor(m, attr("POSITION"), pos, r, what)) {
        r.fail(what + " has no readable POSITION");
        continue;
      }
      const auto& pa = m.accessors[attr("POSITION")];
      if (pa.minValues.size() != 3 || pa.maxValues.size() != 3) {
        r.fail(what + " POSITION lacks min/max");
      } else {
        glm::dvec3 lo(1e30), hi(-1e30);
        for (const auto& p : pos) {
          lo = glm::min(lo, glm::dvec3(p));
          hi = glm::max(hi, glm::dvec3(p));
        }
        for (int c = 0; c < 3; ++c)
          if (static_cast<float>(pa.minValues[c]) != static_cast<float>(lo[c]) ||
              static_cast<float>(pa.maxValues[c]) != static_cast<float>(hi[c]))
            r.fail(what + " POSITION min/max differ from the data");
      }
      for (const char* key : {"NORMAL", "TEXCOORD_0", "TANGENT"}) {
        if (attr(key) >= 0 && m.accessors[attr(key)].count != pos.size()) r.fail(what + " " + key + " count differs");
        if (attr(key) >= 0) {
          const auto& v = m.bufferViews.at(m.accessors[attr(key)].bufferView);
          if (v.target != TINYGLTF_TARGET_ARRAY_BUFFER) r.fail(what + " " + key + " view target is not 34962");
        }
      }
      if (attr("NORMAL") >= 0) read_accessor(m, attr("NORMAL"), nrm, r, what);
      if (attr("TEXCOORD_0") >= 0) read_accessor(m, attr("TEXCOORD_0"), uv, r, what);
      if (attr("TANGENT") >= 0) read_accessor(m, attr("TANGENT"), tan, r, what);
      std::vector<uint32_t> indices;
      if (prim.indices >= 0) {
        const auto& ia = m.accessors[prim.indices];
        if (ia.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT && ia.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)
          r.fail(what + " indices are not u16/u32");
        if (m.bufferViews.at(ia.bufferView).target != TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER)
          r.fail(what + " index view target is not 34963");
        read_accessor(m, prim.indices, idx, r, what);
        bool bad = false;
        for (const auto& i : idx) {
          if (i.x >= static_cast<double>(pos.size())) bad = true;
          indices.push_back(static_cast<uint32_t>(i.x));
        }
        if (bad) {
          r.fail(what + " has an index past the vertex count");
          continue;
        }
      }
      const size_t count = indices.empty() ? pos.size() : indices.size();
      if (count % 3) r.fail(what + " index/vertex count is not a multiple of 3");
      vertices += pos.size();
      triangles += count / 3;
      for (const auto& n : nrm)
        if (std::fabs(glm::length(glm::dvec3(n)) - 1.0) > 1e-4) {
          r.fail(what + " has a non-unit normal");
          break;
        }
      // Winding: the geometric normal agrees with the vertex normals.
      if (!nrm.empty()) {
        size_t wrong = 0;
        for (size_t t = 0; t + 2 < count; t += 3) {
          const uint32_t i0 = indices.empty() ? t : indices[t], i1 = indices.empty() ? t + 1 : indices[t + 1],
                         i2 = indices.empty() ? t + 2 : indices[t + 2];
          const glm::dvec3 g = glm::cross(glm::dvec3(pos[i1] - pos[i0]), glm::dvec3(pos[i2] - pos[i0]));
          if (glm::length(g) < 1e-12) continue;
          if (glm::dot(g, glm::dvec3(nrm[i0] + nrm[i1] + nrm[i2])) <= 0.0) ++wrong;
        }
        if (wrong) r.fail(what + " has " + std::to_string(wrong) + " triangles wound against their normals");
      }
      // Tangents: unit, perpendicular to the normal, w = +-1, and agreeing with the UVs.
      if (!tan.empty()) {
        if (nrm.empty() || uv.empty()) r.fail(what + " has tangents without normals/uvs");
        Mesh mm;
        for (size_t i = 0; i < pos.size(); ++i) {
          mm.positions.push_back(glm::vec3(pos[i]));
          if (!nrm.empty()) mm.normals.push_back(glm::vec3(nrm[i]));
          if (!uv.empty()) mm.uvs.push_back(glm::vec2(uv[i]));
        }
        mm.indices = indices;
        const auto ref = (nrm.empty() || uv.empty()) ? std::vector<glm::vec4>() : compute_tangents(mm);
        size_t bad_unit = 0, bad_dir = 0;
        for (size_t i = 0; i < tan.size(); ++i) {
          const glm::dvec3 t(tan[i]);
          if (std::fabs(glm::length(t) - 1.0) > 1e-4 || std::fabs(std::fabs(tan[i].w) - 1.0) > 1e-6 ||
              (!nrm.empty() && std::fabs(glm::dot(t, glm::dvec3(nrm[i]))) > 1e-4))
            ++bad_unit;
          if (i < ref.size() && ref[i].w != 0.0f && (glm::dot(t, glm::dvec3(ref[i])) < 0.9 || tan[i].w != ref[i].w)) ++bad_dir;
        }
        if (bad_unit) r.fail(what + " has " + std::to_string(bad_unit) + " malformed tangents");
        if (bad_dir) r.fail(what + " has " + std::to_string(bad_dir) + " tangents disagreeing with its UVs");
      }
    }

  if (!print_summary) return;
  std::map<std::string, int> by_type;
  for (const auto& l : m.lights) ++by_type[l.type];
  std::printf("%s: %zu nodes, %zu meshes, %zu vertices, %zu triangles, %zu materials, %zu textures\n", label.c_str(),
              m.nodes.size(), m.meshes.size(), vertices, triangles, m.materials.size(), m.textures.size());
  std::printf("  lights: %zu (", m.lights.size());
  for (const auto& [type, n] : by_type) std::printf(" %s %d", type.c_str(), n);
  std::printf(" )\n  cameras (first = default):");
  for (const auto& c : camera_names) std::printf(" %s", c.c_str());
  std::printf("\n");
  // Exposure: irradiance (largest channel) on sample points of every analytic shape.
  for (const auto& p : probes) {
    std::vector<double> e;
    for (size_t i = 0; i < p.points.size(); ++i) {
      const glm::dvec3 v = irradiance(lights, p.points[i], p.normals[i]);
      e.push_back(std::max(v.x, std::max(v.y, v.z)));
    }
    std::sort(e.begin(), e.end());
    std::printf("  E %-14s min %.3f  p25 %.3f  median %.3f  p75 %.3f  max %.3f\n", p.node.c_str(), e.front(),
                e[e.size() / 4], e[e.size() / 2], e[e.size() * 3 / 4], e.back());
  }
}

std::vector<fs::path> gltf_files(const fs::path& dir) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().extension() == ".gltf") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

int verify_assets(const fs::path& dir) {
  int problems = 0;
  const auto files = gltf_files(dir);
  if (files.empty()) {
    std::fprintf(stderr, "no .gltf files under %s\n", dir.string().c_str());
    return 1;
  }
  for (const auto& path : files) {
    tinygltf::Model model;
    std::string err, warn;
    Report r;
    if (!load(path, model, err, warn)) r.fail("tinygltf failed: " + err);
    else {
      if (!err.empty()) r.fail("tinygltf error: " + err);
      if (!warn.empty()) r.fail("tinygltf warning: " + warn);
      check_model(model, true, r, true, fs::relative(path, dir).string());
    }
    for (const auto& p : r.problems) std::printf("  PROBLEM %s: %s\n", path.string().c_str(), p.c_str());
    problems += static_cast<int>(r.problems.size());
  }
  std::printf("%zu files, %d problems\n", files.size(), problems);
  return problems;
}

int verify_test_data(const fs::path& dir) {
  enum Expect { LoadFails, LoadsWithWarning, LoadsClean };
  const struct {
    const char* file;
    Expect expect;
    const char* convention_problem;  // substring a check_model problem must contain, or null: none
  } cases[] = {
      {"minimal.gltf", LoadsClean, nullptr},
      {"empty_file.gltf", LoadFails, nullptr},
      {"malformed.gltf", LoadFails, nullptr},
      {"missing_buffer.gltf", LoadFails, nullptr},
      {"missing_texture.gltf", LoadsWithWarning, "did not load"},
      {"nonindexed_nonormals.gltf", LoadsClean, nullptr},
      {"no_camera.gltf", LoadsClean, "no camera"},
      {"bad_index.gltf", LoadsClean, "index past the vertex count"},
  };
  int problems = 0;
  for (const auto& c : cases) {
    tinygltf::Model model;
    std::string err, warn;
    const bool ok = load(dir / c.file, model, err, warn);
    auto oneline = [](std::string s) {
      std::replace(s.begin(), s.end(), '\n', ' ');
      return s;
    };
    std::printf("%-26s tinygltf: %s%s%s\n", c.file, ok ? "loaded" : "FAILED", err.empty() ? "" : (" err: " + oneline(err)).c_str(),
                warn.empty() ? "" : (" warn: " + oneline(warn)).c_str());
    bool good = true;
    if (c.expect == LoadFails) good = !ok;
    if (c.expect == LoadsWithWarning) good = ok && !warn.empty();
    if (c.expect == LoadsClean) good = ok && warn.empty() && err.empty();
    if (ok) {
      Report r;
      check_model(model, true, r, false, c.file);
      bool found = c.convention_problem == nullptr;
      for (const auto& p : r.problems) {
        std::printf("    convention check: %s\n", p.c_str());
        if (c.convention_problem && p.find(c.convention_problem) != std::string::npos) found = true;
        else good = false;
      }
      if (!found) good = false;
    }
    if (!good) {
      std::printf("    UNEXPECTED outcome for %s\n", c.file);
      ++problems;
    }
  }
  std::printf("%d unexpected outcomes\n", problems);
  return problems;
}

}  // namespace scenegen
