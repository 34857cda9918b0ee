// Idiom: a compute pass (SSR, SSAO, light culling) runs one invocation per texel, fetches the
// depth with texelFetch at an integer coordinate and goes to NDC from the texel's centre.
//   oblique verify --consumers view_position --precision float --convention all --shader THIS
#version 450 core

vec3 view_position(mat4 inverse_projection, ivec2 texel, vec2 target_size, float depth) {
  vec2 uv = (vec2(texel) + 0.5) / target_size;
  float z = OBLIQUE_CONVENTION == OBLIQUE_GL ? depth * 2.0 - 1.0 : depth;
  vec4 h = inverse_projection * vec4(uv * 2.0 - 1.0, z, 1.0);
  return h.xyz / h.w;
}
