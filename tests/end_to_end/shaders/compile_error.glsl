// A GLSL depth function that does not compile: the driver's message names this file and line.
#version 450 core

vec3 view_position(mat4 inverse_projection, vec2 ndc, float depth) {
  return (inverse_projection * vec4(ndc, depth, 1.0)).xyz + undeclared_name;
}
