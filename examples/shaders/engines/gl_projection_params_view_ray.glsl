// Idiom: the view ray through the pixel from projection parameters (1 / M11, 1 / M22, M13, M23),
// scaled by the view z of the reconstructed point. Rows 1 and 2 of the oblique matrix are the
// camera's, so the ray is right; the z must come from the oblique matrix.
//   oblique verify --consumers view_position --precision float --convention all --shader THIS
// (a function with projection parameters is asked on perspective cameras looking along z)
#version 450 core

vec3 view_position(mat4 inverse_projection, vec4 projection_params, vec2 uv, float depth,
                   float view_axis) {
  vec2 ndc = uv * 2.0 - 1.0;
  float z_ndc = OBLIQUE_CONVENTION == OBLIQUE_GL ? depth * 2.0 - 1.0 : depth;
  vec4 h = inverse_projection * vec4(ndc, z_ndc, 1.0);
  float z = h.z / h.w;
  // clip x = M11 x + M13 z and w = view_axis z: x = z (view_axis ndc x - M13) / M11
  return vec3(z * (view_axis * ndc - projection_params.zw) * projection_params.xy, z);
}
