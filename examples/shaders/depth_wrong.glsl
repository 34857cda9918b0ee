// Depth reconstruction as engines' trackers report it wrong on an oblique depth buffer, one
// function per public class; each is caught (verify --shader FILE:FUNCTION) and named.
#version 450 core

// The camera's own matrix: the depth decompressed with M^-1, not M'^-1 (an HLSL compute shader
// decompressing oblique depth with the non-oblique matrix). Named reconstructs_with_original.
vec3 camera_matrix_view_position(mat4 camera_inverse_projection, vec2 ndc, float depth) {
  float z = OBLIQUE_CONVENTION == OBLIQUE_GL ? 2.0 * depth - 1.0 : depth;
  vec4 v = camera_inverse_projection * vec4(ndc, z, 1.0);
  return v.xyz / v.w;
}

// Linear depth from zparams computed on the CPU from near and far (Unity's LinearEyeDepth).
// Named linearises_with_near_far on [0, 1] depth.
float zparams_linear_depth(vec4 zparams, float depth) {
  return 1.0 / (zparams.z * depth + zparams.w);
}

// [-1, 1] NDC depth on a [0, 1] buffer: OpenGL's mapping whatever the convention. Named
// ndc_depth_of_other_convention (on [0, 1] and reversed-Z depth).
vec3 opengl_ndc_view_position(mat4 inverse_projection, vec2 ndc, float depth) {
  vec4 v = inverse_projection * vec4(ndc, 2.0 * depth - 1.0, 1.0);
  return v.xyz / v.w;
}

// Reversed Z read as forward: the depth flipped before M'^-1, which maps reversed depth already.
// Named reads_reversed_as_forward (on reversed-Z depth).
vec3 reversed_as_forward_view_position(mat4 inverse_projection, vec2 ndc, float depth) {
  float d = OBLIQUE_CONVENTION == OBLIQUE_REVERSED_Z ? 1.0 - depth : depth;
  float z = OBLIQUE_CONVENTION == OBLIQUE_GL ? 2.0 * d - 1.0 : d;
  vec4 v = inverse_projection * vec4(ndc, z, 1.0);
  return v.xyz / v.w;
}
