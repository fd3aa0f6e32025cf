// One local light of the MSAA frame's full-screen loop (MsaaLights::FullScreen), 80 bytes in
// std430: chapter 01's record and where chapter 03 cuts it. Written once for both languages:
// msaa_light.glsl includes this file, and so does msaa.cpp (inside a namespace where vec4 is
// glm::vec4 and GpuLight chapter 01's), so the C++ that packs it and the GLSL that reads it
// cannot drift.
struct LocalLight {
  GpuLight light;
  vec4 cut;  // x: where chapter 03 cuts the light (its volume's radius)
};
