// Wrong twin of cross_api_uv.glsl: the flip under the wrong sense of the platform's define.
#version 450 core

vec3 view_position(mat4 inverse_projection, vec2 texcoord, float depth) {
  vec2 ndc = texcoord * 2.0 - 1.0;
#if !OBLIQUE_UV_V_DOWN
  ndc.y = -ndc.y;
#endif
  float z = OBLIQUE_CONVENTION == OBLIQUE_GL ? depth * 2.0 - 1.0 : depth;
  vec4 h = inverse_projection * vec4(ndc, z, 1.0);
  return h.xyz / h.w;
}
