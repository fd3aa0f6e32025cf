// Moment shadow maps in GLSL: the twins of shadow_math.h's msm_moments, msm_optimize,
// msm_unoptimize and msm_hamburger (its comments derive them), included by the pre-filter
// (shadow_filter.frag: the moments a depth writes) and the lookup (shadow_visibility.glsl), and
// held to the C++ by 06_shadows.gl.GlslTwins.MsmMomentsAndOptimizeMatchTheirCppTwins and
// MsmHamburgerMatchesItsCppTwin.

// shadow_math.h's msm_moments: the four moments (z, z^2, z^3, z^4) of one depth.
vec4 msm_moments(float z) {
  float z2 = z * z;
  return vec4(z, z2, z2 * z, z2 * z2);
}

// shadow_math.h's msm_optimize: the moments through the paper's optimised affine map, stored so
// in a 16-bit map (filtering commutes with it: it is affine, the filter's weights sum to 1).
vec4 msm_optimize(vec4 b) {
  b = mat4(-2.07224649, 13.7948857237, 0.105877704, 9.7924062118,
           32.23703778, -59.4683975703, -1.9077466311, -33.7652110555,
           -68.571074599, 82.0359750338, 9.3496555107, 47.9456096605,
           39.3703274134, -35.364903257, -6.6543490743, -23.9728048165) * b;
  b.x += 0.035955884801;
  return b;
}

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
