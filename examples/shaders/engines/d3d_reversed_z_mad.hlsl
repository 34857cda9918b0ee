// Idiom: a reversed-Z (or [0, 1]) Direct3D 12 / Vulkan-era engine: the stored depth is NDC z as
// is, uv top down to NDC with one mad.
//   oblique verify --consumers view_position --precision float --convention zero_one,reversed_z
//     --shader THIS

float3 view_position(float4x4 inverse_projection, float2 uv, float depth) {
  float4 h = mul(inverse_projection, float4(mad(uv, float2(2.0, -2.0), float2(-1.0, 1.0)), depth,
                                            1.0));
  return h.xyz / h.w;
}
