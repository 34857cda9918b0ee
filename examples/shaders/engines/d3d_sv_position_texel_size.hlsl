// Idiom: a pixel shader takes SV_Position (the pixel's centre in pixels, rows from the top) and
// the target's texel size (1 / width, 1 / height, set on the CPU) and goes to NDC from there.
//   oblique verify --consumers view_position --precision float --convention all --shader THIS

float3 view_position(float4x4 inverse_projection, float4 sv_position, float2 texel_size,
                     float depth) {
  float2 uv = sv_position.xy * texel_size;
  float2 ndc = mad(uv, float2(2.0, -2.0), float2(-1.0, 1.0));
  float z = OBLIQUE_CONVENTION == OBLIQUE_GL ? mad(depth, 2.0, -1.0) : depth;
  float4 h = mul(inverse_projection, float4(ndc, z, 1.0));
  return h.xyz / h.w;
}
