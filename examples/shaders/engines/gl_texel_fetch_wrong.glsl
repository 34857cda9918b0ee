// Wrong twin of gl_texel_fetch.glsl: the texel's corner, not its centre (the + 0.5 left out):
// every pixel is reconstructed on a ray half a pixel down and to the left.
#version 450 core

vec3 view_position(mat4 inverse_projection, ivec2 texel, vec2 target_size, float depth) {
  vec2 uv = vec2(texel) / target_size;
  float z = OBLIQUE_CONVENTION == OBLIQUE_GL ? depth * 2.0 - 1.0 : depth;
  vec4 h = inverse_projection * vec4(uv * 2.0 - 1.0, z, 1.0);
  return h.xyz / h.w;
}
