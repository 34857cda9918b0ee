// Wrong twin of gl_inverse_view_projection_world.glsl: the world position through the camera's
// own projection (the main view's inverse projection, then the inverse view), not through the
// oblique M' the mirror pass drew its depth with.
#version 450 core

vec3 world_position(mat4 camera_inverse_projection, mat4 inverse_view, vec2 uv, float depth) {
#if OBLIQUE_CONVENTION == OBLIQUE_GL
  float z = depth * 2.0 - 1.0;
#else
  float z = depth;
#endif
  vec4 h = camera_inverse_projection * vec4(uv * 2.0 - 1.0, z, 1.0);
  return (inverse_view * vec4(h.xyz / h.w, 1.0)).xyz;
}
