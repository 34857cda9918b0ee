// The wrong reconstructions of depth_wrong.glsl in HLSL, one function per public class.

float3 camera_matrix_view_position(float4x4 camera_inverse_projection, float2 ndc, float depth) {
  float z = OBLIQUE_CONVENTION == OBLIQUE_GL ? 2.0 * depth - 1.0 : depth;
  float4 v = mul(camera_inverse_projection, float4(ndc, z, 1.0));
  return v.xyz / v.w;
}

float zparams_linear_depth(float4 zparams, float depth) {
  return 1.0 / (zparams.z * depth + zparams.w);
}

float3 opengl_ndc_view_position(float4x4 inverse_projection, float2 ndc, float depth) {
  float4 v = mul(inverse_projection, float4(ndc, 2.0 * depth - 1.0, 1.0));
  return v.xyz / v.w;
}

float3 reversed_as_forward_view_position(float4x4 inverse_projection, float2 ndc, float depth) {
  float d = OBLIQUE_CONVENTION == OBLIQUE_REVERSED_Z ? 1.0 - depth : depth;
  float z = OBLIQUE_CONVENTION == OBLIQUE_GL ? 2.0 * d - 1.0 : d;
  float4 v = mul(inverse_projection, float4(ndc, z, 1.0));
  return v.xyz / v.w;
}
