// Depth functions a user gets wrong in ways the harness must refuse clearly (shaders.cmake).
#version 450 core

vec4 returns_vec4(mat4 inverse_projection, vec2 ndc, float depth) {
  return vec4(0.0);
}

vec3 unknown_parameter(mat4 lightViewProj, vec2 ndc, float depth) {
  return vec3(0.0);
}

vec3 depth_as_vec2(mat4 inverse_projection, vec2 ndc, vec2 depth) {
  return vec3(0.0);
}

vec3 writes_nan(mat4 inverse_projection, vec2 ndc, float depth) {
  return vec3(0.0) / 0.0;
}
