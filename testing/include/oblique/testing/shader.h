// Your shader's depth function, as it ships, checked in your test suite: the function is
// compiled into a compute shader (oblique::shader; GLSL, or HLSL through glslang and spirv-cross)
// and run on the GPU path, llvmpipe unless told otherwise, and its answers are judged by the
// consumer properties with the GPU's arithmetic (docs/shaders.md).
//
//   #include <oblique/testing/shader.h>   // link oblique::testing_shader
//
//   OBLIQUE_SHADER_TEST(Ssr, reconstructsViewPosition, "shaders/ssr.glsl", "view_position",
//                       oblique::Contract{})
//
// The function's return type says what it answers (vec3 / float3: view_position; float:
// linear_depth); its parameters are bound by name (inverse_projection, ndc, depth, ...). A
// violation fails the test with the finding, its likely cause and a report, as
// OBLIQUE_CONSUMERS_TEST does. Where the shader cannot compile, the test fails with the
// compiler's messages, lines in your file; without EGL (or, for HLSL, glslang-tools and
// spirv-cross) it is skipped, saying what to install.
#pragma once

#include <string>
#include <vector>

#include "oblique/raster/gl_context.h"
#include "oblique/shader/shader_function.h"
#include "oblique/testing.h"

namespace oblique::testing {

struct ShaderSettings {
  raster::Device device = raster::Device::software;
  /// The longest one dispatch may take before the process is stopped (a shader that hangs).
  double timeout_seconds = 10;
  /// The engine's defines (NAME or NAME=VALUE): the shader's #if variant is the one the
  /// preprocessor keeps under them and OBLIQUE_CONVENTION.
  std::vector<std::string> defines;
  /// Which way the texture coordinate v runs (none: GLSL up, HLSL down; shader_function.h).
  std::optional<shader::VDirection> v;
  /// How its matrices multiply vectors (row: it is handed M^T).
  shader::Vectors vectors = shader::Vectors::column;
  /// Where the function is asked: pixel centres of real targets, or arbitrary positions.
  oracle::Sampling sampling = oracle::Sampling::pixels;
};

/// Checks the function `function` of the shader file `path` against the consumer properties
/// of what it answers, on cases of `contract`; fails the current GoogleTest test on a violation
/// (with a report), skips it where the GPU path cannot run here.
void check_shader(const std::string& path, const std::string& function,
                  const Contract& contract = Contract{},
                  const ShaderSettings& settings = ShaderSettings{});

}  // namespace oblique::testing

/// A GoogleTest test that checks the depth function `function` of the shader file `path` (GLSL,
/// or HLSL by its extension .hlsl / .fx) under `contract`.
#define OBLIQUE_SHADER_TEST(Suite, Name, path, function, contract)    \
  TEST(Suite, Name) {                                                 \
    ::oblique::testing::check_shader((path), (function), (contract)); \
  }

/// OBLIQUE_SHADER_TEST with oblique::testing::ShaderSettings (the engine's defines, the device,
/// the time limit): OBLIQUE_SHADER_TEST_WITH(Ssr, hdrp, "ssr.hlsl", "view_position",
/// oblique::Contract{}, (oblique::testing::ShaderSettings{{}, 10, {"UNITY_REVERSED_Z=1"}})).
#define OBLIQUE_SHADER_TEST_WITH(Suite, Name, path, function, contract, settings) \
  TEST(Suite, Name) {                                                             \
    ::oblique::testing::check_shader((path), (function), (contract), (settings)); \
  }
