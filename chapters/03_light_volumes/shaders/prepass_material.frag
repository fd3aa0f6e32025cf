#version 450
// Deferred lighting's second geometry pass: the object's material applied to the light the
// light buffer holds at its pixel. The specular light arrives as one number.
layout(early_fragment_tests) in;

layout(binding = 0) uniform sampler2D u_base_color_texture;
layout(binding = 2) uniform sampler2D u_emissive_texture;  // glTF: emitted = u_emissive * texel
layout(binding = 5) uniform sampler2D u_light;  // rgb: ambient + diffuse light, a: specular light

uniform vec4 u_base_color;
uniform vec3 u_specular;
uniform vec3 u_emissive;
uniform bool u_chroma;

in vec3 v_position;
in vec3 v_normal;
in vec2 v_uv;
in vec4 v_tangent;

out vec4 out_color;

void main() {
  vec4 light = texelFetch(u_light, ivec2(gl_FragCoord.xy), 0);
  vec3 albedo = (u_base_color * texture(u_base_color_texture, v_uv)).rgb;
  // [prepass-specular]
  vec3 specular_light = vec3(light.a);  // white, whatever colour the lights had
  if (u_chroma) {
    // The usual repair: borrow the colour of the diffuse light here. Right under one light;
    // where lights of different colours overlap, every highlight gets their mix.
    float y = dot(light.rgb, vec3(0.2126, 0.7152, 0.0722));
    specular_light = y > 0.0 ? light.rgb * (light.a / y) : vec3(0.0);
  }
  out_color = vec4(albedo * light.rgb + u_specular * specular_light + u_emissive * texture(u_emissive_texture, v_uv).rgb, 1.0);
  // [/prepass-specular]
}
