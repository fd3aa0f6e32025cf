#pragma once
// Chapter 03's stage: local lights drawn as volumes into a light buffer. Each light covers
// the pixels of its volume; the lighting shader runs only there and adds the light's
// diffuse and specular parts into two float targets; a final full-screen pass combines them
// with the surface (F = albedo * L1 + L2 + emissive). Five strategies decide which pixels
// of a volume reach the shader, from "all of them" to the two-pass stencil mask; all give
// the same image.
//
//   LightVolumes volumes;                          // the unit meshes, the shaders
//   volumes.set_lights(build_light_set(lights, cut_threshold(1.f, peak_reflectance(scene)),
//                                      volumes.shapes()));
//   LightBuffer light(w, h, ch02::depth_format(gbuffer.layout().depth));  // L1, L2, depth-stencil
//   gbuffer.bind_textures(0);                      // the light shaders read chapter 02's G-buffer
//   SurfaceView view = surface_view(gbuffer);
//   light.begin(gbuffer.framebuffer());            // copy its depth, zero the stencil
//   volumes.draw_global(light, view, ambient);     // ambient + directional lights, full screen
//   volumes.draw_local(light, view, Strategy::Stencil);
//   glBindFramebuffer(GL_FRAMEBUFFER, output);  volumes.composite(light, view, background);
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "chapters/02_gbuffer/deferred.h"
#include "chapters/02_gbuffer/gbuffer.h"
#include "chapters/03_light_volumes/fragment_counters.h"
#include "chapters/03_light_volumes/light_instances.h"
#include "chapters/03_light_volumes/volume_meshes.h"
#include "common/camera.h"
#include "common/gl.h"
#include "common/shader.h"

namespace lp::ch03 {

// [strategies]
enum class Strategy {
  FullScreen,  // every pixel, for every light: the reference
  Scissor,     // every pixel of the rectangle around the light's projected sphere
  FrontFaces,  // the volume's front faces, depth test LESS: what lies behind the front
  BackFaces,   // the volume's back faces, depth test GREATER: what lies in front of the back
  Stencil,     // the two-pass stencil mask: exactly what lies inside the volume
  StencilBits, // the same mask, eight lights at a time, one stencil bit each
};
inline const std::vector<std::string> kStrategies = {"full-screen", "scissor", "front-faces", "back-faces", "stencil",
                                                     "stencil-bits"};
// [/strategies]
bool is_strategy(const std::string& name);
Strategy strategy_named(const std::string& name);  // throws Error for an unknown name

// How the global pass (ambient + directional, every pixel) runs: one fragment per pixel of a
// full-screen triangle (chapter 03's own), or one compute invocation per pixel writing the light
// buffer as images. One body (shaders/global_light.glsl): the same light buffer, bit for bit
// on llvmpipe (the tests). Which is faster depends on the GPU: one whose fragment shaders run on
// a few of its cores only (chapter 10's budget) wants compute.
enum class GlobalPass { Fragment, Compute };
inline const std::vector<std::string> kGlobalPasses = {"fragment", "compute"};
GlobalPass global_pass_named(const std::string& name);  // throws Error for an unknown name

// [shader-hooks]
// The GLSL that chapter 03's light shaders include for the terms later chapters add, each a
// file named by a define (`#include FRAME_VISIBILITY`), and the defines those files need (a
// method, the texture units and blocks the frame gave the stage). Chapter 03's own files
// change nothing: every light fully visible, the scene's constant ambient. Chapter 06 names
// its shadow lookup, chapters 07 and 08 their ambient occlusion and indirect light.
struct ShaderHooks {
  // float directional_visibility(int index, GpuLight, Surface); float local_visibility(...)
  std::string visibility = "03_light_volumes/shaders/hooks/full_visibility.glsl";
  // vec3 ambient_light(vec3 ambient, Surface, ivec2 pixel)
  std::string ambient = "03_light_volumes/shaders/hooks/constant_ambient.glsl";
  std::vector<std::string> defines;  // what the files need, e.g. {"SHADOW_METHOD SHADOW_PCF", "SHADOW_UNIT 8"}
  // Everything a program that includes the hooks is compiled with: FRAME_VISIBILITY and
  // FRAME_AMBIENT (the quoted paths), then `defines`.
  std::vector<std::string> glsl_defines() const;
};
// [/shader-hooks]

// What the light shaders read the surface from: chapter 02's G-buffer, or deferred
// lighting's smaller one. Its textures are bound on units 0.. and chapter 02's frame block
// at its binding (GBuffer::bind_textures(0)) before any draw below.
struct SurfaceView {
  FrameCamera camera;                // the camera the G-buffer was drawn with, its projection
  bool reversed_z = false;
  std::vector<std::string> defines;  // gbuffer.glsl's, for the layout
  ShaderHooks hooks;                 // the terms later chapters add (none by default)
};
SurfaceView surface_view(const ch02::GBuffer& gbuffer);

// [light-buffer]
// The light buffer: L1 (diffuse light) and L2 (specular light) in RGBA16F, blended
// additively, and a depth-stencil buffer holding a copy of the G-buffer's depth for the
// volumes' depth tests and the stencil mask. Deferred lighting keeps one target instead:
// rgb diffuse, a specular.
class LightBuffer {
 public:
  enum class Kind { DiffuseAndSpecular, PrePass };
  // Where a pass that reads the light buffer finds it: L1 on unit kFirstUnit, L2 on the next
  // (after the G-buffer's units 0..4). GLSL: `layout(binding = LIGHT_BUFFER_UNIT + 0)`.
  static constexpr GLuint kFirstUnit = ch02::GBuffer::kUnits;
  LightBuffer(int width, int height, GLenum depth_stencil_format, Kind kind = Kind::DiffuseAndSpecular);

  // Copies the depth (and stencil) of `gbuffer_framebuffer`, of the same format, and binds
  // the light buffer. The stencil must be 0 there (chapter 02 clears it and never writes).
  void begin(GLuint gbuffer_framebuffer) const;
  void bind() const;
  void clear() const;  // colours to 0 (the global pass normally overwrites them instead)
  // Binds L1 and L2 to kFirstUnit.. for a pass that reads them; shader_defines() says where.
  void bind_textures() const;
  static std::vector<std::string> shader_defines();  // {"LIGHT_BUFFER_UNIT 5"}
  // Where a compute pass that writes the light buffer finds it as images: L1 on image unit
  // kFirstImage, L2 on the next (RGBA16F). Image units are apart from texture units, and no
  // hook reads an image: a pass binds them just before its dispatch. GLSL:
  // `layout(binding = LIGHT_BUFFER_IMAGE + 0, rgba16f)`.
  static constexpr GLuint kFirstImage = 0;
  void bind_images(GLenum access) const;               // L1 (and L2, not for the pre-pass kind)
  static std::vector<std::string> image_defines();     // {"LIGHT_BUFFER_IMAGE 0"}
  // Runs the bound compute program, 8 x 8 invocations a group, one a pixel, over the buffer
  // (its shader leaves out the groups' overhang), and makes its image writes visible to what
  // reads the light buffer next: image loads, blending, texture reads.
  void dispatch_per_pixel() const;

  GLuint framebuffer() const { return fbo_.id(); }
  GLuint diffuse() const { return diffuse_.id(); }
  GLuint specular() const { return specular_.id(); }  // 0 for the pre-pass kind
  GLuint depth_stencil() const { return depth_stencil_.id(); }
  int width() const { return width_; }
  int height() const { return height_; }
  Kind kind() const { return kind_; }
  std::size_t bytes() const;  // all targets, for the memory report

 private:
  int width_, height_;
  Kind kind_;
  gl::Framebuffer fbo_;
  gl::Texture diffuse_, specular_, depth_stencil_;
};
// [/light-buffer]

// Exact counts of the lighting shader's invocations (64-bit counters made of 32-bit atomics,
// fragment_counters.h; early fragment tests).
struct FragmentCounts {
  std::uint64_t shaded = 0;     // fragments the lighting shader ran for, over all lights
  std::uint64_t lit = 0;        // of those, the ones the light added anything to
  std::uint64_t lit_inner = 0;  // of those, the ones within 99% of the light's cut radius
  std::uint64_t marking = 0;    // fragments of the stencil-marking draws that passed the depth
                                // test: they shade nothing, but GL_SAMPLES_PASSED counts them
                                // (the pass's samples = shaded + marking)
  double overshading() const { return lit ? double(shaded) / double(lit) : 0.0; }
};

// What the CPU did for a strategy in the last draw_local().
struct DrawStats {
  int draw_calls = 0;
  int lights_skipped = 0;         // scissor: the projected sphere is off screen or behind
  int lights_camera_inside = 0;   // front faces: drawn from the back instead
};

// The screen rectangle (x, y, width, height in pixels, OpenGL's bottom-left origin) that
// holds the projection of the sphere (centre, radius) seen by `camera`: the whole viewport
// when the sphere reaches the near plane, nothing when it lies behind it or off screen.
std::optional<glm::ivec4> scissor_rect(const FrameCamera& camera, const glm::vec3& centre, float radius, int width,
                                       int height);

// [volume-hook-h]
// Other convex light volumes through the stencil strategy (chapter 04's capsules): for each
// of `count` volumes, draw(i, VolumePass::Mark) runs with the mask's state and then
// draw(i, VolumePass::Shade) with the light's, exactly as draw_local(Strategy::Stencil) runs
// its own: additive blending, no depth writes, depth clamp. The caller draws volume i with its
// own programs (Mark: any vertex shader with shaders/stencil.frag; Shade: one that writes L1
// and L2 and declares early fragment tests) into the bound framebuffer, whose depth-stencil
// holds the G-buffer's depth and a zero stencil (LightBuffer::begin); each volume leaves the
// stencil at zero again. `stencil_bits`: the bits the masks count in and the light tests
// (write and read masks); the others are neither written nor read, and keep what the caller
// put there (chapter 10's MSAA edge mark, bit 7: its volumes count in bits 0-6).
enum class VolumePass { Mark, Shade };
void draw_stencil_volumes(const SurfaceView& view, int count, const std::function<void(int index, VolumePass pass)>& draw,
                          GLuint stencil_bits = 0xFF);
// [/volume-hook-h]

class LightVolumes {
 public:
  enum class Output { Light, HeatShaded, HeatLit };  // what the lighting shader adds

  explicit LightVolumes(int sphere_subdivisions = 2, int cone_sides = 16);
  void reload_shaders();

  void set_lights(LightSet lights);
  const LightSet& lights() const { return lights_; }
  // lights().directional as uploaded (std430 GpuLight records): for a pass of another stage
  // that lights surfaces with them (chapter 10's glass) instead of uploading them again.
  GLuint directional_buffer() const { return directional_.id(); }
  const VolumeShapes& shapes() const { return shapes_; }

  // Ambient and the directional lights for every pixel; writes the light buffer (no blending),
  // by a fragment pass or a compute pass (`how`, the same values).
  void draw_global(const LightBuffer& target, const SurfaceView& view, const glm::vec3& ambient,
                   GlobalPass how = GlobalPass::Fragment);
  // Every local light, added into the light buffer, the pixels chosen by `strategy`.
  void draw_local(const LightBuffer& target, const SurfaceView& view, Strategy strategy, Output output = Output::Light);
  // F = albedo * L1 + L2 + emissive into the bound framebuffer (sky pixels: background).
  void composite(const LightBuffer& light, const SurfaceView& view, const glm::vec3& background);
  // The same colours written by a compute pass into `image`, an RGBA16F texture the light
  // buffer's size (a float target's colour: FrameOutput::image).
  void composite_compute(const LightBuffer& light, const SurfaceView& view, const glm::vec3& background, GLuint image);

  // Counting costs an atomic operation per fragment: on for tests and the panel, off for timing.
  // The counters start each draw_local at `start` (0; tests start them near 2^32 to see them
  // cross it), and counts() returns start + what was counted.
  void set_counting(bool on, std::uint64_t start = 0) {
    counting_ = on;
    count_start_ = start;
  }
  bool counting() const { return counting_; }
  FragmentCounts counts() const;  // of the last draw_local (waits for the GPU)
  const DrawStats& draw_stats() const { return stats_; }

  // For draw_stencil_volumes with these lights and other light shaders (chapter 10's MSAA):
  // a program of volume.vert (the light records as its outputs) and `fragment`, its
  // view-projection set; and local light `index`'s volume (light order) drawn with it.
  const ShaderProgram& volume_program(const std::string& fragment, const SurfaceView& view,
                                      std::vector<std::string> extra = {});
  void draw_volume(const ShaderProgram& program, int index) const;

  // Pictures, into the bound framebuffer, whose depth-stencil holds the scene's depth:
  // every volume as a wireframe in its light's colour, depth-tested against the scene.
  void draw_wireframe(const SurfaceView& view);
  // One light's stencil mask (the pixels its light pass shades) tinted in its colour,
  // with its volume's outline. `index` counts in light order; the stencil is left at 0.
  void draw_stencil_mask(const SurfaceView& view, int index);
  // A per-pixel count from a light buffer drawn with Output::Heat*, as a colour ramp.
  void draw_heat(const LightBuffer& counts, float full_scale);
  // One light-buffer target (diffuse() or specular()) times `scale`.
  void draw_light_target(GLuint texture, float scale);

 private:
  struct Group;  // the lights drawn with one mesh and one record type
  // The program for a fragment shader, with volume.vert (volumes = true) or a full-screen
  // triangle, compiled once for each set of defines.
  const ShaderProgram& program(const std::string& fragment, const SurfaceView& view, std::vector<std::string> extra = {},
                               bool volumes = true);
  // A compute shader's, with the same defines (the G-buffer's layout, the hooks, `extra`).
  const ShaderProgram& compute_program(const std::string& compute, const SurfaceView& view, std::vector<std::string> extra);
  std::vector<Group> groups() const;
  void draw_group(const Group& g, const ShaderProgram& p, int first, int count, bool full_screen) const;
  // The strategies, one function each, called by draw_local() between its common set-up
  // (programs, counters, additive blending, depth clamp) and restoring OpenGL's defaults.
  struct Draw;
  void draw_full_screen(const Draw& d);
  void draw_scissor(const Draw& d);
  void draw_front_faces(const Draw& d);
  void draw_back_faces(const Draw& d);
  void draw_stencil(const Draw& d);
  void draw_stencil_bits(const Draw& d);
  void set_volume_uniforms(const ShaderProgram& p, const SurfaceView& view) const;
  bool camera_inside(const Group& g, int i, const glm::vec3& eye) const;

  VolumeShapes shapes_;
  LightSet lights_;
  gl::Buffer sphere_vertices_, sphere_indices_, cone_vertices_, cone_indices_;
  gl::Buffer points_, cones_, wide_spots_, directional_;
  FragmentCounters counters_{4};  // shaded, lit, lit_inner (light.frag), marking (stencil.frag)
  std::uint64_t count_start_ = 0;
  gl::VertexArray points_vao_, cones_vao_, wide_vao_;
  ProgramCache programs_;
  ch02::FullScreenPass full_screen_;
  bool counting_ = false;
  DrawStats stats_;
};

}  // namespace lp::ch03
