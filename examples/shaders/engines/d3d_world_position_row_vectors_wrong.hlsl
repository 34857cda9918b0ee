// Wrong twin of d3d_world_position_row_vectors.hlsl: the view-space point carried by the view
// matrix (world to camera) where its inverse belongs.

float3 world_position(row_major float4x4 inverse_projection, row_major float4x4 view,
                      float2 uv, float depth) {
  float z = OBLIQUE_CONVENTION == OBLIQUE_GL ? depth * 2.0 - 1.0 : depth;
  float4 h = mul(float4(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, z, 1.0), inverse_projection);
  float3 view_position = h.xyz / h.w;
  return mul(float4(view_position, 1.0), view).xyz;
}
