// Idiom: a deferred or SSR pass reconstructs the pixel's world position through the inverse of
// the pass's view-projection (set on the CPU per pass: for a mirror or portal pass, the oblique
// M' times the pass camera's view), from the pixel's uv.
//   oblique verify --consumers world_position --precision float --convention all --shader THIS
#version 450 core

vec3 world_position(mat4 inverse_view_projection, vec2 uv, float depth) {
#if OBLIQUE_CONVENTION == OBLIQUE_GL
  float z = depth * 2.0 - 1.0;
#else
  float z = depth;
#endif
  vec4 h = inverse_view_projection * vec4(uv * 2.0 - 1.0, z, 1.0);
  return h.xyz / h.w;
}
