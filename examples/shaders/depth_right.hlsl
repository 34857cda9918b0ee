// Depth reconstruction in HLSL (run through glslang and spirv-cross), with the inverse of the
// oblique M' the depth was rendered with, in every depth convention.
// oblique verify --consumers view_position,linear_depth --shader examples/shaders/depth_right.hlsl

float NdcDepth(float depth) {
#if OBLIQUE_CONVENTION == OBLIQUE_GL
  return 2.0 * depth - 1.0;
#else
  return depth;
#endif
}

float3 view_position(float4x4 inverse_projection, float2 ndc, float depth) {
  float4 v = mul(inverse_projection, float4(ndc, NdcDepth(depth), 1.0));
  return v.xyz / v.w;
}

float linear_depth(float4x4 inverse_projection, float2 ndc, float depth, float view_axis) {
  return view_axis * view_position(inverse_projection, ndc, depth).z;
}
