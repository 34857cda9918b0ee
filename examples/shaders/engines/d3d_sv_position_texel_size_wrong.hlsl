// Wrong twin of d3d_sv_position_texel_size.hlsl: the fast path that ignores the oblique row,
// solving view z from the projection's z entries alone (M33, M34, M43) and x and y by dividing by
// M11 and M22, as if the matrix had no tilt.

float3 view_position(float4x4 projection, float4 sv_position, float2 texel_size, float depth) {
  float2 uv = sv_position.xy * texel_size;
  float2 ndc = mad(uv, float2(2.0, -2.0), float2(-1.0, 1.0));
  float z_ndc = OBLIQUE_CONVENTION == OBLIQUE_GL ? mad(depth, 2.0, -1.0) : depth;
  // z_ndc = (M33 z + M34) / (M43 z)
  float z = projection[2][3] / (z_ndc * projection[3][2] - projection[2][2]);
  float w = projection[3][2] * z;
  return float3((ndc.x * w - projection[0][2] * z) / projection[0][0],
                (ndc.y * w - projection[1][2] * z) / projection[1][1], z);
}
