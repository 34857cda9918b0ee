// An HLSL depth function that does not compile: glslang's message names this file and line.

float3 view_position(float4x4 inverse_projection, float2 ndc, float depth) {
  return mul(inverse_projection, float4(ndc, depth, 1.0)).xyz + undeclared_name;
}
