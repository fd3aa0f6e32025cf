#version 450
// The GPU side of tests/unit/glsl_twin.h: evaluates one GLSL expression over per-case inputs
// (four vec4, a, b, c and d) and writes one vec4 per case. The shader files under test are included
// by computed includes (TWIN_FILE_0..3, each a quoted path; unused ones name twin_nothing.glsl),
// so the test runs the chapter's own file, never a copy.
#include TWIN_FILE_0
#include TWIN_FILE_1
#include TWIN_FILE_2
#include TWIN_FILE_3

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Cases { vec4 cases[]; };     // a, b, c, d: 4 per case
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };  // 1 per case

uniform int u_count;

// Functions the expression calls, one line (the test's `helpers`).
TWIN_HELPERS

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uint(u_count)) return;
  vec4 a = cases[4u * i], b = cases[4u * i + 1u], c = cases[4u * i + 2u], d = cases[4u * i + 3u];
  results[i] = vec4(TWIN_EXPRESSION);
}
