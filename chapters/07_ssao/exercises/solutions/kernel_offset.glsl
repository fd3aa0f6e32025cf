// Exercise 2 of chapter 07, solved: the same function as 07_ssao/shaders/ssao.comp.
vec3 kernel_point(vec3 p, vec3 offset, float radius) { return p + radius * (mat3(u_view) * offset); }
