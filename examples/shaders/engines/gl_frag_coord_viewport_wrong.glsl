// Wrong twin of gl_frag_coord_viewport.glsl: inverts the camera's own projection in the shader
// (the uniform the main view's passes share) instead of the oblique matrix of the mirror pass.
#version 450 core

vec3 view_position(mat4 camera_projection, vec2 frag_coord, vec4 viewport, float depth) {
  vec2 ndc = (frag_coord - viewport.xy) / viewport.zw * 2.0 - 1.0;
  float z = OBLIQUE_CONVENTION == OBLIQUE_GL ? depth * 2.0 - 1.0 : depth;
  vec4 h = inverse(camera_projection) * vec4(ndc, z, 1.0);
  return h.xyz / h.w;
}
