// Depth reconstruction as a deferred or post pass should write it: with the inverse of the
// matrix the depth was rendered with (the oblique M'), in every depth convention.
// oblique verify --consumers view_position,linear_depth --shader examples/shaders/depth_right.glsl
#version 450 core

float ndc_depth(float depth) {
#if OBLIQUE_CONVENTION == OBLIQUE_GL
  return 2.0 * depth - 1.0;  // [-1, 1] NDC from the [0, 1] window depth
#else
  return depth;  // [0, 1] and reversed Z: the window depth is NDC z
#endif
}

vec3 view_position(mat4 inverse_projection, vec2 ndc, float depth) {
  vec4 v = inverse_projection * vec4(ndc, ndc_depth(depth), 1.0);
  return v.xyz / v.w;
}

// The distance in front of the camera along its view axis: view_axis z (view_axis = -1 for a
// camera looking down -z).
float linear_depth(mat4 inverse_projection, vec2 ndc, float depth, float view_axis) {
  return view_axis * view_position(inverse_projection, ndc, depth).z;
}
