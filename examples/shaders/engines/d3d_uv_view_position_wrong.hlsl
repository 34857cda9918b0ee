// Wrong twin of d3d_uv_view_position.hlsl: GL's uv * 2 - 1 on a top-down texture coordinate, so
// every pixel is reconstructed on the ray of the pixel mirrored in y.

float3 view_position(float4x4 inverse_projection, float2 uv, float depth) {
#if OBLIQUE_CONVENTION == OBLIQUE_GL
  float z = depth * 2.0 - 1.0;
#else
  float z = depth;
#endif
  float4 h = mul(inverse_projection, float4(uv * 2.0 - 1.0, z, 1.0));
  return h.xyz / h.w;
}
