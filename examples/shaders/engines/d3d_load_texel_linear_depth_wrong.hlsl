// Wrong twin of d3d_load_texel_linear_depth.hlsl: Unity's LinearEyeDepth on _ZBufferParams,
// 1 / (zparams.z d + zparams.w), built from the camera's near and far planes.

float linear_depth(float4 zbuffer_params, int2 texel, float depth) {
  return 1.0 / (zbuffer_params.z * depth + zbuffer_params.w);
}
