// gpu_probe [--size WxH] [--iterations N] [--layers L] [--runs R]: the same arithmetic in a
// fragment shader and in a compute shader, and a pass that writes one colour per pixel from
// each, timed with GL_TIME_ELAPSED (the median of R runs after a warm-up). Writes CSV to
// standard output. What it shows: how much of the GPU each kind of shader reaches (on an
// NVIDIA H200 only a few of its SMs run pixel shaders; book/00-introduction.md).
#include <algorithm>
#include <charconv>
#include <chrono>
#include <functional>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "common/cli.h"
#include "common/context.h"
#include "common/error.h"
#include "common/gl.h"

namespace {

using lp::Error;

GLuint compile(GLenum kind, const std::string& source) {
  const GLuint s = glCreateShader(kind);
  const char* text = source.c_str();
  glShaderSource(s, 1, &text, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[4096];
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    throw Error(std::string("gpu_probe: a shader does not compile: ") + log);
  }
  return s;
}

GLuint program(std::vector<std::pair<GLenum, std::string>> stages) {
  const GLuint p = glCreateProgram();
  for (const auto& [kind, source] : stages) glAttachShader(p, compile(kind, source));
  glLinkProgram(p);
  GLint ok = 0;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) throw Error("gpu_probe: a program does not link");
  return p;
}

// The work: ITERATIONS steps of two dependent fused multiply-adds, from the pixel's position,
// so that nothing folds away; the result is written, so nothing is dropped.
const std::string kWork = R"(
float work(vec2 p) {
  float x = p.x * 1e-3, y = p.y * 1e-3;
  for (int i = 0; i < ITERATIONS; ++i) { x = fma(x, 0.9999, y); y = fma(y, 0.9998, x); }
  return x + y;
})";
const std::string kVertex = R"(#version 450
void main() { gl_Position = vec4(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0, 0.0, 1.0); })";

struct Row {
  std::string test, stage;
  double work_per_pixel = 0, ms = 0, rate = 0;
  std::string unit;
};

// The median time of `runs` runs of `pass`, after three not counted: the GPU's own clock
// (GL_TIME_ELAPSED), or, on a software renderer, whose queries time the submission rather
// than the work, the wall clock around the pass and a glFinish (a CPU timing).
double median_ms(int runs, bool wall_clock, const std::function<void()>& pass) {
  lp::gl::Query query(GL_TIME_ELAPSED);
  std::vector<double> ms;
  for (int r = 0; r < runs + 3; ++r) {
    glFinish();
    const auto start = std::chrono::steady_clock::now();
    if (!wall_clock) glBeginQuery(GL_TIME_ELAPSED, query.id());
    pass();
    double t = 0;
    if (wall_clock) {
      glFinish();
      t = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    } else {
      glEndQuery(GL_TIME_ELAPSED);
      GLuint64 ns = 0;
      glGetQueryObjectui64v(query.id(), GL_QUERY_RESULT, &ns);
      t = double(ns) * 1e-6;
    }
    if (r >= 3) ms.push_back(t);
  }
  std::sort(ms.begin(), ms.end());
  return ms[ms.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  try {
    int w = 1920, h = 1080, iterations = 4096, layers = 64, runs = 7;
    try {  // the options: a usage error exits with 2, as every program of the book's does
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto value = [&]() -> std::string {
        if (i + 1 >= argc) throw Error("gpu_probe: " + a + " needs a value");
        return argv[++i];
      };
      auto positive = [&](const std::string& v) {
        int n = 0;
        const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), n);
        if (ec != std::errc() || end != v.data() + v.size() || n <= 0 || n > 1 << 20)
          throw Error("gpu_probe: " + a + " must be a whole number between 1 and 2^20, not '" + v + "'");
        return n;
      };
      if (a == "--size") {
        const std::string v = value();
        if (std::sscanf(v.c_str(), "%dx%d", &w, &h) != 2 || w <= 0 || h <= 0 || w > 16384 || h > 16384)
          throw Error("gpu_probe: --size must be WxH (1 to 16384 each), not " + v);
      } else if (a == "--iterations") iterations = positive(value());
      else if (a == "--layers") layers = positive(value());
      else if (a == "--runs") runs = positive(value());
      else throw Error("gpu_probe: unknown option " + a + " (--size WxH, --iterations N, --layers L, --runs R)");
    }
    } catch (const std::exception& e) {
      std::cerr << "error: " << e.what() << '\n';
      return 2;
    }
    auto context = lp::Context::create({.headless = true, .width = w, .height = h});
    const std::string defines = "#define ITERATIONS " + std::to_string(iterations) + "\n";
    const GLuint fragment_work = program({{GL_VERTEX_SHADER, kVertex},
                                          {GL_FRAGMENT_SHADER, "#version 450\n" + defines + kWork +
                                                                   "\nout float o; void main() { o = work(gl_FragCoord.xy); }"}});
    const GLuint compute_work = program({{GL_COMPUTE_SHADER, "#version 450\nlayout(local_size_x = 8, local_size_y = 8) in;\n" + defines +
                                                                "layout(r32f, binding = 0) writeonly uniform image2D o;\n" + kWork +
                                                                "\nvoid main() { ivec2 p = ivec2(gl_GlobalInvocationID.xy);"
                                                                " if (all(lessThan(p, imageSize(o)))) imageStore(o, p, vec4(work(vec2(p) + 0.5))); }"}});
    const GLuint fragment_fill = program({{GL_VERTEX_SHADER, kVertex},
                                          {GL_FRAGMENT_SHADER, "#version 450\nout vec4 o; void main() { o = vec4(0.2, 0.4, 0.6, 1.0); }"}});
    const GLuint compute_fill = program({{GL_COMPUTE_SHADER, "#version 450\nlayout(local_size_x = 8, local_size_y = 8) in;\n"
                                                               "layout(rgba8, binding = 0) writeonly uniform image2D o;\n"
                                                               "void main() { ivec2 p = ivec2(gl_GlobalInvocationID.xy);"
                                                               " if (all(lessThan(p, imageSize(o)))) imageStore(o, p, vec4(0.2, 0.4, 0.6, 1.0)); }"}});
    lp::gl::Texture r32f = lp::gl::make_texture_2d(GL_R32F, w, h), rgba8 = lp::gl::make_texture_2d(GL_RGBA8, w, h);
    lp::gl::Framebuffer to_r32f, to_rgba8;
    glNamedFramebufferTexture(to_r32f.id(), GL_COLOR_ATTACHMENT0, r32f.id(), 0);
    glNamedFramebufferTexture(to_rgba8.id(), GL_COLOR_ATTACHMENT0, rgba8.id(), 0);
    lp::gl::VertexArray vao;
    glBindVertexArray(vao.id());
    glDisable(GL_DEPTH_TEST), glDisable(GL_BLEND), glDisable(GL_CULL_FACE);
    glViewport(0, 0, w, h);
    const bool wall = context->is_software();
    const GLuint gx = GLuint((w + 7) / 8), gy = GLuint((h + 7) / 8);
    const double pixels = double(w) * double(h), flops = 4.0 * iterations;  // two FMAs, four flops, a step
    std::vector<Row> rows;
    auto arithmetic = [&](const char* stage, double ms) {
      rows.push_back({"arithmetic", stage, flops, ms, pixels * flops / (ms * 1e-3) * 1e-12, "TFLOP/s"});
    };
    auto fill = [&](const char* stage, double ms) {
      rows.push_back({"fill", stage, double(layers), ms, pixels * layers / (ms * 1e-3) * 1e-9, "Gpixel/s"});
    };
    glBindFramebuffer(GL_FRAMEBUFFER, to_r32f.id());
    glUseProgram(fragment_work);
    arithmetic("fragment", median_ms(runs, wall, [] { glDrawArrays(GL_TRIANGLES, 0, 3); }));
    glUseProgram(compute_work);
    glBindImageTexture(0, r32f.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    arithmetic("compute", median_ms(runs, wall, [&] { glDispatchCompute(gx, gy, 1); }));
    glBindFramebuffer(GL_FRAMEBUFFER, to_rgba8.id());
    glUseProgram(fragment_fill);
    fill("fragment", median_ms(runs, wall, [&] { for (int l = 0; l < layers; ++l) glDrawArrays(GL_TRIANGLES, 0, 3); }));
    glUseProgram(compute_fill);
    glBindImageTexture(0, rgba8.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
    fill("compute", median_ms(runs, wall, [&] {
      for (int l = 0; l < layers; ++l) {
        glDispatchCompute(gx, gy, 1);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);  // each layer after the last, as blending-free draws are
      }
    }));
    if (const GLenum e = glGetError(); e != GL_NO_ERROR) throw Error("gpu_probe: GL error " + std::to_string(e));
    std::cout << "# gpu_probe: " << context->renderer() << "; " << w << "x" << h << ", median of " << runs
              << " runs (" << (wall ? "wall clock and glFinish: a CPU timing" : "GL_TIME_ELAPSED") << "); work = flops per pixel (arithmetic) or writes per pixel (fill)\n"
              << "renderer,test,stage,width,height,work,ms,rate,unit\n";
    for (const Row& r : rows)
      std::cout << '"' << context->renderer() << "\"," << r.test << ',' << r.stage << ',' << w << ',' << h << ','
                << r.work_per_pixel << ',' << r.ms << ',' << r.rate << ',' << r.unit << '\n';
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << '\n';
    return 1;
  }
}
