#!/bin/sh
# make_hostile_shaders.sh DIR: writes the hostile shader files of issue 64 into DIR (made at test
# time: some are megabytes). Each holds the right reconstruction (view_position through the inverse
# of M') unless its name says otherwise, so a right verdict is the answer where the file is valid.
set -e
dir=$1
mkdir -p "$dir"
right='vec3 view_position(mat4 inverse_projection, vec2 ndc, float depth) {
#if OBLIQUE_CONVENTION == OBLIQUE_GL
  float z = 2.0 * depth - 1.0;
#else
  float z = depth;
#endif
  vec4 v = inverse_projection * vec4(ndc, z, 1.0);
  return v.xyz / v.w;
}'
# Comments after a word, 900 lines of them (about 50 KB): std::regex recursed once per character.
{
  echo "#version 450 core"
  i=0
  while [ $i -lt 900 ]; do echo "// a comment line of some length, as a licence header has it ....."; i=$((i + 1)); done
  echo "$right"
} > "$dir/comments_after_version.glsl"
{
  echo "#version 450 core"
  echo "#ifdef SOMETHING"
  echo "#endif"
  i=0
  while [ $i -lt 900 ]; do echo "// a comment line of some length, as a licence header has it ....."; i=$((i + 1)); done
  echo "$right"
} > "$dir/comments_after_endif.glsl"
# A 50 KB identifier.
long=$(head -c 51200 /dev/zero | tr '\0' 'a')
{
  echo "const float $long = 1.0;"
  echo "$right"
} > "$dir/long_identifier.glsl"
# A 300 KB #version line (the wrapper gives its own #version: the line goes).
{
  printf '#version 450 core '
  head -c 307200 /dev/zero | tr '\0' ' '
  echo
  echo "$right"
} > "$dir/long_version_line.glsl"
# A 10,000-parameter function.
{
  printf 'vec3 view_position(mat4 inverse_projection, vec2 ndc, float depth'
  i=0
  while [ $i -lt 10000 ]; do printf ', float extra%d' $i; i=$((i + 1)); done
  echo ') { return vec3(0.0); }'
} > "$dir/ten_thousand_parameters.glsl"
# A macro bomb: 39 doubling #defines, used once (2^39 tokens).
{
  echo "#define M0 depth"
  i=1
  while [ $i -le 39 ]; do echo "#define M$i M$((i - 1)) + M$((i - 1))"; i=$((i + 1)); done
  echo 'vec3 view_position(mat4 inverse_projection, vec2 ndc, float depth) { return vec3(M39); }'
} > "$dir/macro_bomb.glsl"
# The same bomb in an HLSL #if: glslang's preprocessor spins on it.
{
  echo "#define M0 1"
  i=1
  while [ $i -le 39 ]; do echo "#define M$i (M$((i - 1)) + M$((i - 1)))"; i=$((i + 1)); done
  echo "#if M39 > 0"
  echo "#endif"
  echo 'float3 view_position(float4x4 inverse_projection, float2 ndc, float depth) { return float3(0, 0, 0); }'
} > "$dir/if_bomb.hlsl"
# 15 MB of functions after the right one (glslang and the driver take minutes on it).
{
  echo "$right"
  i=0
  while [ $i -lt 4 ]; do
    awk -v k=$i 'BEGIN { for (j = 0; j < 57000; ++j) printf "float filler_%d_%d(float x) { return x * 2.0 + 1.0 - 0.5 * x; }\n", k, j }'
    i=$((i + 1))
  done
} > "$dir/fifteen_megabytes.glsl"
# A wrong function that writes a right answer into its neighbour's slot through a buffer declared
# at the runner's answer binding (caught in the run, and its replay said "the round holds").
cat > "$dir/writes_its_neighbour.glsl" <<'GLSL'
layout(std430, binding = 1) buffer Neighbours { vec4 answers[]; };
vec3 view_position(mat4 inverse_projection, vec2 ndc, float depth) {
  float z = OBLIQUE_CONVENTION == OBLIQUE_GL ? 2.0 * depth - 1.0 : depth;
  vec4 v = inverse_projection * vec4(ndc, z, 1.0);
  answers[gl_GlobalInvocationID.x + 1u] = vec4(v.xyz / v.w, 0.0);
  return v.xyz / v.w * 1.5;
}
GLSL
# The same through a macro that pastes the names together.
cat > "$dir/writes_its_neighbour_pasted.glsl" <<'GLSL'
#define PASTE(a, b) a##b
layout(std430, binding = 1) PASTE(buf, fer) Neighbours { vec4 answers[]; };
vec3 view_position(mat4 inverse_projection, vec2 ndc, float depth) {
  vec4 v = inverse_projection * vec4(ndc, depth, 1.0);
  answers[PASTE(gl_GlobalInvocation, ID).x + 1u] = vec4(v.xyz / v.w, 0.0);
  return v.xyz / v.w * 1.5;
}
GLSL
