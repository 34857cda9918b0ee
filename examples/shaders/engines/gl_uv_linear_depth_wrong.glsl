// Wrong twin of gl_uv_linear_depth.glsl: the textbook linearisation from the camera's near and
// far distances (a perspectiveDepthToViewZ-style helper), which the oblique matrix no longer has.
#version 450 core

float linear_depth(float near, float far, float depth) {
  float r = near / far;  // 0 for an infinite far plane: the formulas below stay finite
#if OBLIQUE_CONVENTION == OBLIQUE_GL
  float z = depth * 2.0 - 1.0;
  return 2.0 * near / (1.0 + r - z * (1.0 - r));
#elif OBLIQUE_CONVENTION == OBLIQUE_ZERO_ONE
  return near / (1.0 - depth * (1.0 - r));
#else
  return near / (r + depth * (1.0 - r));
#endif
}
