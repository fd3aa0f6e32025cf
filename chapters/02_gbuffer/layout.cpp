#include "chapters/02_gbuffer/layout.h"

#include "common/error.h"
#include "common/gl.h"

namespace lp::ch02 {

GLenum normal_format(NormalEncoding e) {
  switch (e) {
    case NormalEncoding::Float: return GL_RGBA32F;
    case NormalEncoding::Xyz10: return GL_RGB10_A2;
    case NormalEncoding::Oct8: return GL_RG8;
    case NormalEncoding::Oct10: return GL_RGB10_A2;
    case NormalEncoding::Oct16: return GL_RG16;
  }
  return GL_NONE;
}

GLenum depth_format(DepthFormat d) {
  return d == DepthFormat::D24S8 ? GL_DEPTH24_STENCIL8 : GL_DEPTH32F_STENCIL8;
}

bool has_control_bits(const Layout& l) {
  return l.normal == NormalEncoding::Xyz10 || l.normal == NormalEncoding::Oct10 || l.normal == NormalEncoding::Float;
}

bool is_reversed_z(const Layout& l) { return l.depth == DepthFormat::D32FS8Reversed; }

std::string normal_encoding_name(NormalEncoding e) {
  switch (e) {
    case NormalEncoding::Float: return "xyz float32";
    case NormalEncoding::Xyz10: return "xyz 10+10+10 (RGB10A2)";
    case NormalEncoding::Oct8: return "octahedral 8+8 (RG8)";
    case NormalEncoding::Oct10: return "octahedral 10+10 (RGB10A2)";
    case NormalEncoding::Oct16: return "octahedral 16+16 (RG16)";
  }
  return "?";
}

std::string depth_format_name(DepthFormat d) {
  switch (d) {
    case DepthFormat::D24S8: return "D24S8";
    case DepthFormat::D32FS8: return "D32F_S8";
    case DepthFormat::D32FS8Reversed: return "D32F_S8 reversed-Z";
  }
  return "?";
}

std::size_t bytes_per_pixel(const Layout& l) {
  std::size_t colour = gl::bytes_per_texel(l.colour_format);
  std::size_t bytes = 2 * colour + gl::bytes_per_texel(normal_format(l.normal)) + gl::bytes_per_texel(depth_format(l.depth));
  if (l.depth_target) bytes += gl::bytes_per_texel(GL_R32F);
  if (l.stored_position) bytes += gl::bytes_per_texel(GL_RGBA32F);
  return bytes;
}

std::string format_name(GLenum f) {
  switch (f) {
    case GL_RGBA8: return "GL_RGBA8";
    case GL_SRGB8_ALPHA8: return "GL_SRGB8_ALPHA8";
    case GL_RGBA32F: return "GL_RGBA32F";
    case GL_RGB10_A2: return "GL_RGB10_A2";
    case GL_RG8: return "GL_RG8";
    case GL_RG16: return "GL_RG16";
    case GL_R32F: return "GL_R32F";
    case GL_DEPTH24_STENCIL8: return "GL_DEPTH24_STENCIL8";
    case GL_DEPTH32F_STENCIL8: return "GL_DEPTH32F_STENCIL8";
    default: return "?";
  }
}

std::vector<TargetInfo> targets(const Layout& l) {
  auto bytes = [](GLenum f) { return gl::bytes_per_texel(f); };
  std::string emissive = l.emissive == EmissiveStorage::AlbedoScale ? "a emissive strength (x albedo)" : "a emissive code";
  std::string exponent = l.colour_format == GL_RGBA32F ? "a exponent" : "a exponent (8-bit log2)";
  std::string normal = l.normal == NormalEncoding::Float ? "xyz normal, a control"
                       : l.normal == NormalEncoding::Xyz10 ? "xyz normal * 0.5 + 0.5, a 2-bit control"
                       : l.normal == NormalEncoding::Oct10 ? "rg octahedral normal, b spare, a 2-bit control"
                                                            : "rg octahedral normal";
  std::vector<TargetInfo> t = {
      {"albedo", format_name(l.colour_format), bytes(l.colour_format), "rgb albedo, " + emissive},
      {"specular", format_name(l.colour_format), bytes(l.colour_format), "rgb specular colour, " + exponent},
      {"normal", format_name(normal_format(l.normal)), bytes(normal_format(l.normal)), normal},
  };
  if (l.depth_target) t.push_back({"depth copy", "GL_R32F", bytes(GL_R32F), "window depth (the thesis's G4)"});
  if (l.stored_position) t.push_back({"position", "GL_RGBA32F", bytes(GL_RGBA32F), "xyz world position"});
  std::string depth = is_reversed_z(l) ? "depth (reversed-Z), stencil free" : "depth, stencil free";
  t.push_back({"depth-stencil", format_name(depth_format(l.depth)), bytes(depth_format(l.depth)), depth});
  return t;
}

// [layouts]
const std::vector<Layout>& layouts() {
  static const std::vector<Layout> all = {
      {.name = "ours", .description = "RGBA8 albedo + emissive code | RGBA8 specular + log2 exponent | octahedral RG16 normal | D24S8",
       .normal = NormalEncoding::Oct16, .depth = DepthFormat::D24S8, .colour_format = GL_RGBA8},
      {.name = "source", .description = "the thesis: RGBA8 albedo + emissive | RGBA8 specular + exponent | RGB10A2 normal + control | R32F depth | D24S8",
       .normal = NormalEncoding::Xyz10, .depth = DepthFormat::D24S8, .colour_format = GL_RGBA8,
       .emissive = EmissiveStorage::AlbedoScale, .depth_target = true},
      {.name = "float", .description = "reference: everything in RGBA32F, world position stored; D24S8 like chapter 01's target",
       .normal = NormalEncoding::Float, .depth = DepthFormat::D24S8, .colour_format = GL_RGBA32F, .stored_position = true},
      {.name = "xyz10", .description = "ours with the source's xyz normal in RGB10A2",
       .normal = NormalEncoding::Xyz10, .depth = DepthFormat::D24S8, .colour_format = GL_RGBA8},
      {.name = "oct8", .description = "ours with an octahedral RG8 normal",
       .normal = NormalEncoding::Oct8, .depth = DepthFormat::D24S8, .colour_format = GL_RGBA8},
      {.name = "oct10", .description = "ours with an octahedral 10+10 normal in RGB10A2 (+ 2 control bits)",
       .normal = NormalEncoding::Oct10, .depth = DepthFormat::D24S8, .colour_format = GL_RGBA8},
      {.name = "srgb-colour", .description = "ours with sRGB8 albedo and specular colour",
       .normal = NormalEncoding::Oct16, .depth = DepthFormat::D24S8, .colour_format = GL_SRGB8_ALPHA8},
      {.name = "d32f", .description = "ours with D32F_S8 depth, standard direction",
       .normal = NormalEncoding::Oct16, .depth = DepthFormat::D32FS8, .colour_format = GL_RGBA8},
      {.name = "reversed-z", .description = "ours with D32F_S8 depth, reversed-Z",
       .normal = NormalEncoding::Oct16, .depth = DepthFormat::D32FS8Reversed, .colour_format = GL_RGBA8},
  };
  return all;
}
// [/layouts]

const Layout& layout_named(const std::string& name) {
  std::string names;
  for (const auto& l : layouts()) {
    if (l.name == name) return l;
    names += (names.empty() ? "" : ", ") + l.name;
  }
  throw Error("no G-buffer layout named '" + name + "'; layouts: " + names);
}

const Layout& our_layout() { return layouts()[0]; }
const Layout& source_layout() { return layout_named("source"); }
const Layout& float_layout() { return layout_named("float"); }

Layout float_reference_for(const Layout& layout) {
  Layout l = float_layout();
  if (layout.depth == l.depth) return l;
  l.name = "float-" + depth_format_name(layout.depth);
  l.depth = layout.depth;
  return l;
}

}  // namespace lp::ch02
