// Idiom: a GL fragment shader divides gl_FragCoord.xy (the pixel's centre, rows from the bottom)
// by the target's resolution uniform to get uv, then NDC.
//   oblique verify --consumers view_position --precision float --convention all --shader THIS
#version 450 core

vec3 view_position(mat4 inverse_projection, vec4 frag_coord, vec2 resolution, float depth) {
  vec2 ndc = frag_coord.xy / resolution * 2.0 - 1.0;
  float z = OBLIQUE_CONVENTION == OBLIQUE_GL ? depth * 2.0 - 1.0 : depth;
  vec4 h = inverse_projection * vec4(ndc, z, 1.0);
  return h.xyz / h.w;
}
