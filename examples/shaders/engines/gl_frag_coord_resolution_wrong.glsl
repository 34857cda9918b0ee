// Wrong twin of gl_frag_coord_resolution.glsl: the window depth mapped to NDC as OpenGL does,
// 2 d - 1, whatever the depth convention (code ported from GL to a [0, 1] or reversed-Z API).
#version 450 core

vec3 view_position(mat4 inverse_projection, vec4 frag_coord, vec2 resolution, float depth) {
  vec2 ndc = frag_coord.xy / resolution * 2.0 - 1.0;
  vec4 h = inverse_projection * vec4(ndc, depth * 2.0 - 1.0, 1.0);
  return h.xyz / h.w;
}
