// One function in two variants, as engines ship them: the preprocessor keeps one under the
// engine's defines. ENGINE_INVERSE_ON_GPU=1 keeps the right one (the inverse of M' it is given);
// without it the other variant takes NDC z as GL's 2 d - 1 in every convention, wrong on [0, 1]
// and reversed Z.
#version 450 core

#if defined(ENGINE_INVERSE_ON_GPU) && ENGINE_INVERSE_ON_GPU
vec3 view_position(mat4 inverse_projection, vec2 ndc, float depth) {
#if OBLIQUE_CONVENTION == OBLIQUE_GL
  float z = 2.0 * depth - 1.0;
#else
  float z = depth;
#endif
  vec4 v = inverse_projection * vec4(ndc, z, 1.0);
  return v.xyz / v.w;
}
#else
vec3 view_position(mat4 inverse_projection, vec2 ndc, float depth) {
  vec4 v = inverse_projection * vec4(ndc, 2.0 * depth - 1.0, 1.0);
  return v.xyz / v.w;
}
#endif
