// Wrong twin of d3d_reversed_z_mad.hlsl: turns the reversed depth forward (1 - d), as a
// linearisation written for forward depth needs, before an inverse that already maps reversed
// depth.

float3 view_position(float4x4 inverse_projection, float2 uv, float depth) {
#if OBLIQUE_CONVENTION == OBLIQUE_REVERSED_Z
  depth = 1.0 - depth;
#endif
  float4 h = mul(inverse_projection, float4(mad(uv, float2(2.0, -2.0), float2(-1.0, 1.0)), depth,
                                            1.0));
  return h.xyz / h.w;
}
