// Idiom: a Direct3D engine with row vectors reconstructs the world position in two steps: the
// view-space point through the inverse projection, then the inverse view (camera to world), each
// a row vector times the matrix as its constant buffer holds it.
//   oblique verify --consumers world_position --precision float --convention all --vectors row
//     --shader THIS

float3 world_position(row_major float4x4 inverse_projection,
                      row_major float4x4 inverse_view, float2 uv, float depth) {
  float z = OBLIQUE_CONVENTION == OBLIQUE_GL ? depth * 2.0 - 1.0 : depth;
  float4 h = mul(float4(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, z, 1.0), inverse_projection);
  float3 view_position = h.xyz / h.w;
  return mul(float4(view_position, 1.0), inverse_view).xyz;
}
