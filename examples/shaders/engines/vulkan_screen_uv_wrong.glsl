// Wrong twin of vulkan_screen_uv.glsl: flips y as a Direct3D port does, on an API whose NDC y
// already points down: every pixel is reconstructed on the ray of the pixel mirrored in y.
#version 450 core

vec3 view_position(mat4 inv_projection, vec2 screen_uv, float depth) {
  vec2 ndc = vec2(screen_uv.x * 2.0 - 1.0, 1.0 - screen_uv.y * 2.0);
  vec4 h = inv_projection * vec4(ndc, depth, 1.0);
  return h.xyz / h.w;
}
