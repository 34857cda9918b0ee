// Idiom: a GL post pass (SSAO, SSR, decals) hands the reconstruction the full-screen triangle's
// uv, v up, and maps it to NDC with uv * 2 - 1; the depth to NDC z by the convention; then the
// inverse of the matrix the depth was rendered with.
//   oblique verify --consumers view_position --precision float --convention all --shader THIS
#version 450 core

vec3 view_position(mat4 inverse_projection, vec2 uv, float depth) {
#if OBLIQUE_CONVENTION == OBLIQUE_GL
  float z = depth * 2.0 - 1.0;
#else
  float z = depth;
#endif
  vec4 h = inverse_projection * vec4(uv * 2.0 - 1.0, z, 1.0);
  return h.xyz / h.w;
}
