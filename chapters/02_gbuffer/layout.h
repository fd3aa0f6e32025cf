#pragma once
// What a G-buffer stores and in which formats. Every layout the chapter compares is one of
// these; `kOurs` is the one the book chooses (and the measurements that chose it are in
// book/02-gbuffer.md).
#include <string>
#include <vector>

#include <epoxy/gl.h>

namespace lp::ch02 {

// How the surface normal is stored.
enum class NormalEncoding {
  Float,  // xyz in RGBA32F: the lossless reference
  Xyz10,  // the source's naive n * 0.5 + 0.5 in RGB10A2
  Oct8,   // octahedral, 8 + 8 bits (RG8)
  Oct10,  // octahedral, 10 + 10 bits in RGB10A2 (blue spare, alpha: 2 control bits)
  Oct16,  // octahedral, 16 + 16 bits (RG16)
};

// The depth-stencil buffer, and which way depth runs.
enum class DepthFormat {
  D24S8,           // GL_DEPTH24_STENCIL8, standard OpenGL depth (-1..1 clip z, LESS)
  D32FS8,          // GL_DEPTH32F_STENCIL8, standard
  D32FS8Reversed,  // GL_DEPTH32F_STENCIL8, reversed-Z: 1 at the near plane, 0 at the far plane
};

// How the emissive colour is kept.
enum class EmissiveStorage {
  AlbedoScale,  // the source: an 8-bit strength that multiplies the albedo
  Palette,      // an 8-bit index into the frame's table of emissive material colours
};

struct Layout {
  std::string name;         // "ours", "source", "float", ...
  std::string description;  // one line for the book and the panel
  NormalEncoding normal = NormalEncoding::Oct16;
  DepthFormat depth = DepthFormat::D24S8;
  GLenum colour_format = GL_RGBA8;  // albedo and specular targets
  EmissiveStorage emissive = EmissiveStorage::Palette;
  bool depth_target = false;     // the source's G4: window depth copied to an R32F target
  bool stored_position = false;  // world position in an RGBA32F target (the float reference)
};

// One render target of a layout, for the program's report and the book's tables.
struct TargetInfo {
  std::string name;      // "albedo", "specular", "normal", "depth copy", "position", "depth-stencil"
  std::string format;    // "GL_SRGB8_ALPHA8", ...
  std::size_t bytes;     // per pixel
  std::string contents;  // "rgb albedo, a emissive code"
};
std::vector<TargetInfo> targets(const Layout& layout);
std::string format_name(GLenum format);

// Bytes per pixel of every target (colour + depth-stencil), as gl::bytes_per_texel counts them.
std::size_t bytes_per_pixel(const Layout& layout);
GLenum normal_format(NormalEncoding e);
GLenum depth_format(DepthFormat d);
bool has_control_bits(const Layout& layout);  // a 2-bit alpha in the normal target marks geometry
bool is_reversed_z(const Layout& layout);
std::string normal_encoding_name(NormalEncoding e);
std::string depth_format_name(DepthFormat d);

// The layouts the chapter compares. kLayouts[0] is ours.
const std::vector<Layout>& layouts();
const Layout& layout_named(const std::string& name);  // throws Error listing the names
const Layout& our_layout();
const Layout& source_layout();
const Layout& float_layout();
// The float layout with `layout`'s depth buffer: it makes the same depth-test decisions, so
// comparing the two measures what the formats lose, not which surface won.
Layout float_reference_for(const Layout& layout);

}  // namespace lp::ch02
