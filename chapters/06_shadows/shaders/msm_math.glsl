// Moment shadow maps in GLSL: the twin of shadow_math.h's msm_unoptimize and msm_hamburger (its
// comments derive them), included by the lookup (shadow_visibility.glsl) and held to the C++ by
// 06_shadows.gl.GlslTwins.MsmHamburgerMatchesItsCppTwin.

// [msm-glsl]
// shadow_math.h's msm_unoptimize: the moments back from the optimised 16-bit map.
vec4 msm_unoptimize(vec4 b) {
  b.x -= 0.035955884801;
  return mat4(0.2227744146, 0.1549679261, 0.1451988946, 0.163127443,
              0.0771972861, 0.1394629426, 0.2120202157, 0.2591432266,
              0.7926986636, 0.7963415838, 0.7258694464, 0.6539092497,
              0.0319417555, -0.1722823173, -0.2758014811, -0.3376131734) * b;
}

// shadow_math.h's msm_hamburger: the moments pulled towards 0.5, the Hankel matrix's Cholesky
// factors, the two other support points, and the weight in front of the receiver at depth d.
float msm_hamburger(vec4 b, float d, float moment_bias) {
  b = mix(b, vec4(0.5), moment_bias);
  float l32_d22 = -b.x * b.y + b.z;
  float d22 = -b.x * b.x + b.y;
  float squared_variance = -b.y * b.y + b.w;
  float d33_d22 = squared_variance * d22 - l32_d22 * l32_d22;
  if (d22 <= 0.0) return d <= b.x ? 1.0 : 0.0;  // one depth: the guards of shadow_math.cpp
  float inv_d22 = 1.0 / d22;
  float l32 = l32_d22 * inv_d22;
  vec3 c = vec3(1.0, d, d * d);
  if (d33_d22 <= 0.0) {
    c = vec3(l32 * b.x - b.y, -l32, 1.0);  // a singular Hankel matrix: its kernel's quadratic
  } else {
    c.y -= b.x;
    c.z -= b.y + l32 * c.y;
    c.y *= inv_d22;
    c.z *= d22 / d33_d22;
    c.y -= l32 * c.z;
    c.x -= c.y * b.x + c.z * b.y;
  }
  if (abs(c.y) >= 1048576.0 * abs(c.z)) {  // the quadratic is a line: one root, the other at infinity
    float r1 = -c.x / c.y;
    return 1.0 - clamp(r1 < d ? (d - b.x) / (d - r1) : 0.0, 0.0, 1.0);
  }
  float p = c.y / c.z, q = c.x / c.z;
  float r = sqrt(max(p * p * 0.25 - q, 0.0));
  float z1 = -p * 0.5 - r, z2 = -p * 0.5 + r;
  vec4 sw = z2 < d ? vec4(z1, d, 1.0, 1.0) : z1 < d ? vec4(d, z1, 0.0, 1.0) : vec4(0.0);
  float quotient = sw.w > 0.0 ? (sw.x * z2 - b.x * (sw.x + z2) + b.y) / ((z2 - sw.y) * (d - z1)) : 0.0;
  return 1.0 - clamp(sw.z + sw.w * quotient, 0.0, 1.0);
}
// [/msm-glsl]
