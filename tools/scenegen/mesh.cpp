#include "mesh.h"

#include <cmath>
#include <numbers>

namespace scenegen {

namespace {

// sin/cos of 2*pi*i/n with exact values at the quarter turns, so that symmetric meshes stay
// exactly symmetric (and poles/seams land on exact coordinates).
void sincos_fraction(int i, int n, float& s, float& c) {
  if ((4 * i) % n == 0) {
    static constexpr float kS[4] = {0, 1, 0, -1};
    static constexpr float kC[4] = {1, 0, -1, 0};
    int q = ((4 * i) / n) % 4;
    s = kS[q];
    c = kC[q];
    return;
  }
  double a = 2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(n);
  s = static_cast<float>(std::sin(a));
  c = static_cast<float>(std::cos(a));
}

// Quad (a top-left, b top-right, c bottom-left, d bottom-right as seen from the front).
void push_quad(std::vector<uint32_t>& idx, uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
  idx.insert(idx.end(), {a, c, d, a, d, b});
}

}  // namespace

void Mesh::append(const Mesh& other, const glm::mat4& xf) {
  const uint32_t base = static_cast<uint32_t>(positions.size());
  const glm::mat3 m(xf);
  const glm::mat3 nm = glm::transpose(glm::inverse(m));
  const float handed = glm::determinant(m) < 0.0f ? -1.0f : 1.0f;
  for (const auto& p : other.positions) positions.push_back(glm::vec3(xf * glm::vec4(p, 1.0f)));
  for (const auto& n : other.normals) normals.push_back(glm::normalize(nm * n));
  for (const auto& uv : other.uvs) uvs.push_back(uv);
  for (const auto& t : other.tangents) tangents.push_back(glm::vec4(glm::normalize(m * glm::vec3(t)), t.w * handed));
  if (other.indices.empty()) {
    for (uint32_t i = 0; i < other.positions.size(); ++i) indices.push_back(base + i);
  } else {
    for (uint32_t i : other.indices) indices.push_back(base + i);
  }
}

glm::mat3 face_frame(const glm::vec3& normal, const glm::vec3& x_axis) {
  return glm::mat3(x_axis, normal, glm::cross(x_axis, normal));
}

Mesh make_uv_sphere(float radius, int segments, int rings) {
  Mesh m;
  const int cols = segments + 1;
  for (int r = 0; r <= rings; ++r) {
    float st, ct;  // polar angle theta = pi * r / rings
    sincos_fraction(r, 2 * rings, st, ct);
    const bool pole = (r == 0 || r == rings);
    for (int s = 0; s <= segments; ++s) {
      // Pole vertices sit at the middle of their segment (one per triangle fan blade).
      float sp, cp;
      float u;
      if (pole) {
        sincos_fraction(2 * s + 1, 2 * segments, sp, cp);
        u = (static_cast<float>(s) + 0.5f) / static_cast<float>(segments);
      } else {
        sincos_fraction(s, segments, sp, cp);
        u = static_cast<float>(s) / static_cast<float>(segments);
      }
      const glm::vec3 n(st * sp, ct, st * cp);
      m.positions.push_back(radius * n);
      m.normals.push_back(n);
      m.uvs.push_back({u, static_cast<float>(r) / static_cast<float>(rings)});
      m.tangents.push_back({cp, 0.0f, -sp, 1.0f});
    }
  }
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      const uint32_t a = static_cast<uint32_t>(r * cols + s), b = a + 1;
      const uint32_t c = a + static_cast<uint32_t>(cols), d = c + 1;
      if (r == 0) {
        m.indices.insert(m.indices.end(), {a, c, d});  // a is the north pole
      } else if (r == rings - 1) {
        m.indices.insert(m.indices.end(), {a, c, b});  // c is the south pole
      } else {
        push_quad(m.indices, a, b, c, d);
      }
    }
  }
  return m;
}

Mesh make_rect(float sx, float sz, int div_x, int div_z, glm::vec2 uv_scale) {
  Mesh m;
  for (int j = 0; j <= div_z; ++j) {
    const float fz = static_cast<float>(j) / static_cast<float>(div_z);
    for (int i = 0; i <= div_x; ++i) {
      const float fx = static_cast<float>(i) / static_cast<float>(div_x);
      m.positions.push_back({(fx - 0.5f) * sx, 0.0f, (fz - 0.5f) * sz});
      m.normals.push_back({0, 1, 0});
      m.uvs.push_back({fx * uv_scale.x, fz * uv_scale.y});
      m.tangents.push_back({1, 0, 0, 1});
    }
  }
  const uint32_t cols = static_cast<uint32_t>(div_x + 1);
  for (int j = 0; j < div_z; ++j)
    for (int i = 0; i < div_x; ++i) {
      const uint32_t a = static_cast<uint32_t>(j) * cols + static_cast<uint32_t>(i);
      // Seen from +Y with -Z "up": a is top-left, a+1 top-right, a+cols bottom-left.
      push_quad(m.indices, a, a + 1, a + cols, a + cols + 1);
    }
  return m;
}

Mesh make_box(const glm::vec3& size, float uv_per_metre) {
  struct Face {
    glm::vec3 n, x;
    float sx, sz, offset;
  };
  const Face faces[6] = {
      {{1, 0, 0}, {0, 0, -1}, size.z, size.y, size.x * 0.5f},
      {{-1, 0, 0}, {0, 0, 1}, size.z, size.y, size.x * 0.5f},
      {{0, 1, 0}, {1, 0, 0}, size.x, size.z, size.y * 0.5f},
      {{0, -1, 0}, {1, 0, 0}, size.x, size.z, size.y * 0.5f},
      {{0, 0, 1}, {1, 0, 0}, size.x, size.y, size.z * 0.5f},
      {{0, 0, -1}, {-1, 0, 0}, size.x, size.y, size.z * 0.5f},
  };
  Mesh box;
  for (const Face& f : faces) {
    glm::mat4 xf(face_frame(f.n, f.x));
    xf[3] = glm::vec4(f.n * f.offset, 1.0f);
    box.append(make_rect(f.sx, f.sz, 1, 1, glm::vec2(f.sx, f.sz) * uv_per_metre), xf);
  }
  return box;
}

Mesh make_cylinder(float radius, float height, int segments, glm::vec2 uv_scale) {
  Mesh m;
  const int cols = segments + 1;
  for (int row = 0; row <= 1; ++row) {
    const float y = row == 0 ? height : 0.0f;  // top row first: v grows downwards
    for (int s = 0; s <= segments; ++s) {
      float sp, cp;
      sincos_fraction(s, segments, sp, cp);
      const glm::vec3 n(sp, 0.0f, cp);
      m.positions.push_back({radius * sp, y, radius * cp});
      m.normals.push_back(n);
      m.uvs.push_back({uv_scale.x * static_cast<float>(s) / static_cast<float>(segments), uv_scale.y * static_cast<float>(row)});
      m.tangents.push_back({cp, 0.0f, -sp, 1.0f});
    }
  }
  for (int s = 0; s < segments; ++s) {
    const uint32_t a = static_cast<uint32_t>(s);
    push_quad(m.indices, a, a + 1, a + static_cast<uint32_t>(cols), a + static_cast<uint32_t>(cols) + 1);
  }
  return m;
}

Mesh make_half_torus(float major, float minor, int major_segments, int minor_segments, glm::vec2 uv_scale) {
  Mesh m;
  const int cols = minor_segments + 1;
  for (int i = 0; i <= major_segments; ++i) {
    float su, cu;  // u in [0, pi]
    sincos_fraction(i, 2 * major_segments, su, cu);
    const glm::vec3 er(cu, su, 0.0f), eu(-su, cu, 0.0f), ez(0.0f, 0.0f, 1.0f);
    for (int k = 0; k <= minor_segments; ++k) {
      float sv, cv;
      sincos_fraction(k, minor_segments, sv, cv);
      const glm::vec3 n = cv * er + sv * ez;
      glm::vec3 p = major * er + minor * n;
      if (i == 0 || i == major_segments) p.y = 0.0f;  // exact flat ends
      m.positions.push_back(p);
      m.normals.push_back(n);
      // v decreases with the minor angle so that bitangent (-v) = d/dv_angle and w = +1.
      m.uvs.push_back({uv_scale.x * static_cast<float>(i) / static_cast<float>(major_segments),
                       uv_scale.y * (1.0f - static_cast<float>(k) / static_cast<float>(minor_segments))});
      m.tangents.push_back(glm::vec4(eu, 1.0f));
    }
  }
  for (int i = 0; i < major_segments; ++i)
    for (int k = 0; k < minor_segments; ++k) {
      const uint32_t p00 = static_cast<uint32_t>(i * cols + k), p01 = p00 + 1;
      const uint32_t p10 = p00 + static_cast<uint32_t>(cols), p11 = p10 + 1;
      m.indices.insert(m.indices.end(), {p00, p10, p01, p10, p11, p01});
    }
  return m;
}

std::vector<glm::vec4> compute_tangents(const Mesh& mesh) {
  const size_t n = mesh.positions.size();
  std::vector<glm::vec3> tan(n, glm::vec3(0.0f)), bit(n, glm::vec3(0.0f));
  const size_t count = mesh.indices.empty() ? n : mesh.indices.size();
  auto index = [&](size_t i) -> uint32_t { return mesh.indices.empty() ? static_cast<uint32_t>(i) : mesh.indices[i]; };
  for (size_t t = 0; t + 2 < count; t += 3) {
    const uint32_t i0 = index(t), i1 = index(t + 1), i2 = index(t + 2);
    const glm::vec3 e1 = mesh.positions[i1] - mesh.positions[i0], e2 = mesh.positions[i2] - mesh.positions[i0];
    const glm::vec2 d1 = mesh.uvs[i1] - mesh.uvs[i0], d2 = mesh.uvs[i2] - mesh.uvs[i0];
    const float det = d1.x * d2.y - d2.x * d1.y;
    if (std::fabs(det) < 1e-12f || glm::length(glm::cross(e1, e2)) < 1e-12f) continue;
    const float r = 1.0f / det;
    const glm::vec3 sdir = (e1 * d2.y - e2 * d1.y) * r;  // dP/du
    const glm::vec3 tdir = (e2 * d1.x - e1 * d2.x) * r;  // dP/dv
    for (uint32_t i : {i0, i1, i2}) {
      tan[i] += sdir;
      bit[i] += tdir;
    }
  }
  std::vector<glm::vec4> out(n, glm::vec4(0.0f));
  for (size_t i = 0; i < n; ++i) {
    const glm::vec3 nn = mesh.normals[i];
    glm::vec3 t = tan[i] - nn * glm::dot(nn, tan[i]);
    if (glm::length(t) < 1e-12f) continue;  // unused or degenerate vertex
    t = glm::normalize(t);
    // Bitangent points along -v (glTF's image "up").
    const float w = glm::dot(glm::cross(nn, t), -bit[i]) < 0.0f ? -1.0f : 1.0f;
    out[i] = glm::vec4(t, w);
  }
  return out;
}

}  // namespace scenegen
