// [neon-gpu]
// One tube as the shaders see it (std430, 96 bytes): the thesis's per-instance matrix M, the
// barn doors and what it has no room for. Written once for both languages: neon.glsl includes
// this file, and so does capsule.h (inside a namespace where mat4 and vec4 are glm's).
//
//   row 0:  Ri x volume radius    | colour.r x intensity       Ri, Rj, Rk: orthonormal and
//   row 1:  Rj x half length      | colour.g x intensity       right-handed; Rj is the axis,
//   row 2:  Rk x specular         | colour.b x intensity       Ri the first door's side
//   row 3:  centre S = (A + B)/2  | caps (1 capsule, 0 cylinder)
//
// m[i] is a column in both GLSL and glm, so `rows` holds the ROWS of M: rows[0] is row 0
// above. As a vertex attribute (mat4, locations k .. k+3) each row arrives as one vec4, as in
// the thesis.
struct NeonGpu {
  mat4 rows;
  vec4 barn_doors;  // distance, count, transmittance, softness (count 0: none)
  vec4 extra;       // x: the glass tube's radius; y: the doors' radius; zw: 0
};
// [/neon-gpu]
