// Idiom: linear depth for fog, soft particles or depth of field as the distance along the view
// axis of the reconstructed point (fma(uv, 2, -1) to NDC), not a near/far formula.
//   oblique verify --consumers linear_depth --precision float --convention all --shader THIS
#version 450 core

float linear_depth(mat4 inverse_projection, vec2 uv, float depth, float view_axis) {
  float z = OBLIQUE_CONVENTION == OBLIQUE_GL ? fma(depth, 2.0, -1.0) : depth;
  vec4 h = inverse_projection * vec4(fma(uv, vec2(2.0), vec2(-1.0)), z, 1.0);
  return view_axis * (h.z / h.w);
}
