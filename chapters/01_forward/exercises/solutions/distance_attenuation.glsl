// Exercise 2 of chapter 01, solved: the same function as 01_forward/shaders/lighting.glsl.
float distance_attenuation(float distance, float range) {
  float d2 = max(distance * distance, 1e-4);
  float window = 1.0;
  if (range > 0.0) {
    float ratio = distance / range;
    window = clamp(1.0 - ratio * ratio * ratio * ratio, 0.0, 1.0);
    window *= window;
  }
  return window / d2;
}
