// Wrong twin of gl_projection_params_view_ray.glsl: the view z from the camera's near and far
// distances (the textbook formula), which the oblique matrix's depth no longer follows.
#version 450 core

vec3 view_position(vec4 projection_params, vec2 uv, float depth, float near, float far,
                   float view_axis) {
  vec2 ndc = uv * 2.0 - 1.0;
  float r = near / far;  // 0 for an infinite far plane: the formulas below stay finite
#if OBLIQUE_CONVENTION == OBLIQUE_GL
  float distance = 2.0 * near / (1.0 + r - (depth * 2.0 - 1.0) * (1.0 - r));
#elif OBLIQUE_CONVENTION == OBLIQUE_ZERO_ONE
  float distance = near / (1.0 - depth * (1.0 - r));
#else
  float distance = near / (r + depth * (1.0 - r));
#endif
  float z = view_axis * distance;
  return vec3(z * (view_axis * ndc - projection_params.zw) * projection_params.xy, z);
}
