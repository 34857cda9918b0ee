// The same reconstruction with the inverse taken in the shader (GLSL's inverse(), on the GPU's
// arithmetic) from the oblique projection itself.
#version 450 core

vec3 view_position(mat4 projection, vec2 ndc, float depth) {
  float z = OBLIQUE_CONVENTION == OBLIQUE_GL ? 2.0 * depth - 1.0 : depth;
  vec4 v = inverse(projection) * vec4(ndc, z, 1.0);
  return v.xyz / v.w;
}
