// Idiom: a Vulkan engine (Godot 4's style): NDC y already points down the image, so the screen uv
// runs with it (v = (NDC y + 1) / 2, --uv-v up) and needs no flip; depth is [0, 1] or reversed.
//   oblique verify --consumers view_position --precision float --convention zero_one,reversed_z
//     --shader THIS
#version 450 core

vec3 view_position(mat4 inv_projection, vec2 screen_uv, float depth) {
  vec4 h = inv_projection * vec4(screen_uv * 2.0 - 1.0, depth, 1.0);
  return h.xyz / h.w;
}
