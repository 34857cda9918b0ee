// A depth function that takes long: a loop of 65535 sines in every invocation (llvmpipe caps a
// loop at 65535 iterations; a GPU driver may not cap it at all). verify --timeout 0.001 must stop
// it with a clear message and exit status 2 (a dispatch cannot be cancelled).
vec3 view_position(mat4 inverse_projection, vec2 ndc, float depth) {
  float x = depth;
  while (depth < 2.0) x += sin(x);
  return vec3(x);
}
