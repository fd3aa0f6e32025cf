// Exercise 1 of chapter 03, solved: the same function as 01_forward/shaders/lighting.glsl.
float range_window(float distance, float range) {
  float window = 1.0;
  if (range > 0.0) {
    float ratio = distance / range;
    window = clamp(1.0 - ratio * ratio * ratio * ratio, 0.0, 1.0);
    window *= window;
  }
  return window;
}
