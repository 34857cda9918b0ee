// Idiom: the viewport as a vec4 (x, y, width, height) beside gl_FragCoord, as engines that draw
// into a part of a larger target pass it: NDC = (frag - offset) / size * 2 - 1.
//   oblique verify --consumers view_position --precision float --convention all --shader THIS
#version 450 core

vec3 view_position(mat4 projection, vec2 frag_coord, vec4 viewport, float depth) {
  vec2 ndc = (frag_coord - viewport.xy) / viewport.zw * 2.0 - 1.0;
  float z = OBLIQUE_CONVENTION == OBLIQUE_GL ? depth * 2.0 - 1.0 : depth;
  vec4 h = inverse(projection) * vec4(ndc, z, 1.0);
  return h.xyz / h.w;
}
