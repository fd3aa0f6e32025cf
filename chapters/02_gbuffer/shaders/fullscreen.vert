#version 450
// One triangle that covers the whole viewport (and more): vertices (-1,-1), (3,-1), (-1,3).
// Unlike two triangles it has no diagonal seam where pixels are shaded twice.
void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
