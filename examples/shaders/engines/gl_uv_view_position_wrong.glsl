// Wrong twin of gl_uv_view_position.glsl: the inverse of the camera's own projection (the one the
// main view keeps), not of the oblique matrix the mirror pass drew its depth with.
#version 450 core

vec3 view_position(mat4 camera_inverse_projection, vec2 uv, float depth) {
#if OBLIQUE_CONVENTION == OBLIQUE_GL
  float z = depth * 2.0 - 1.0;
#else
  float z = depth;
#endif
  vec4 h = camera_inverse_projection * vec4(uv * 2.0 - 1.0, z, 1.0);
  return h.xyz / h.w;
}
