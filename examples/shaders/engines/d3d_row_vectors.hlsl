// Idiom: a Direct3D engine with row vectors (DirectXMath, D3DX): points are rows, v * M, and its
// uniforms hold M^T; the parameter is declared row_major as its constant buffer is.
//   oblique verify --consumers view_position --precision float --convention all --vectors row
//     --shader THIS

float3 view_position(row_major float4x4 inverse_projection, float2 uv, float depth) {
  float z = OBLIQUE_CONVENTION == OBLIQUE_GL ? depth * 2.0 - 1.0 : depth;
  float4 h = mul(float4(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, z, 1.0), inverse_projection);
  return h.xyz / h.w;
}
