// Idiom: a Direct3D or Metal pass reads uv top down (v = 0 at the top row) and maps it to NDC
// with y flipped: (2 u - 1, 1 - 2 v).
//   oblique verify --consumers view_position --precision float --convention all --shader THIS
// (HLSL's default is --uv-v down.)

float3 view_position(float4x4 inverse_projection, float2 uv, float depth) {
#if OBLIQUE_CONVENTION == OBLIQUE_GL
  float z = depth * 2.0 - 1.0;
#else
  float z = depth;
#endif
  float2 ndc = float2(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0);
  float4 h = mul(inverse_projection, float4(ndc, z, 1.0));
  return h.xyz / h.w;
}
