// Wrong twin of d3d_row_vectors.hlsl: a column-vector product, mul(M, v), ported from GL code, on a
// matrix stored for row vectors: the transpose of the right product.

float3 view_position(row_major float4x4 inverse_projection, float2 uv, float depth) {
  float z = OBLIQUE_CONVENTION == OBLIQUE_GL ? depth * 2.0 - 1.0 : depth;
  float4 h = mul(inverse_projection, float4(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, z, 1.0));
  return h.xyz / h.w;
}
