// Idiom: a Direct3D compute pass reads the depth with Load at an integer texel (rows from the
// top) and the texel size, and takes linear depth from the reconstructed view position.
//   oblique verify --consumers linear_depth --precision float --convention all --shader THIS

float linear_depth(float4x4 inverse_projection, int2 texel, float2 texel_size, float depth,
                   float view_axis) {
  float2 uv = (float2(texel) + 0.5) * texel_size;
  float2 ndc = float2(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0);
  float z = OBLIQUE_CONVENTION == OBLIQUE_GL ? depth * 2.0 - 1.0 : depth;
  float4 h = mul(inverse_projection, float4(ndc, z, 1.0));
  return view_axis * h.z / h.w;
}
