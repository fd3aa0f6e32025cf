// Exercise 2 of chapter 08, solved: the same function as 08_ssgi/shaders/ssgi.comp.
vec2 pattern_point(int i, vec2 jitter) {
  if (u_pattern == 0) {
    int ring = i / u_spokes, spoke = i % u_spokes;
    float a = 2.0 * PI * float(spoke) / float(u_spokes);
    return sqrt((float(ring) + 0.5) / float(u_rings)) * vec2(cos(a), sin(a));
  }
  float offset = u_pattern == 2 ? jitter.y : 0.5;
  float a = 2.39996323 * float(i) + (u_pattern == 2 ? 2.0 * PI * jitter.x : 0.0);
  return sqrt((float(i) + offset) / float(u_samples)) * vec2(cos(a), sin(a));
}
