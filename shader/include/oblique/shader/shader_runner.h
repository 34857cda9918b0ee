// A user's depth functions (shader_function.h) compiled into compute shaders on the headless
// OpenGL context (oblique/raster/gl_context.h: llvmpipe, or the machine's GPU) and run on
// batches of depth samples: tens of thousands of requests per dispatch, each answer read back
// for the consumer judges (oblique/oracle/consumers.h, with the GPU's arithmetic).
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "oblique/expected.h"
#include "oblique/oracle/consumers.h"
#include "oblique/raster/gl_context.h"
#include "oblique/shader/shader_function.h"

namespace oblique::shader {

struct RunnerOptions {
  raster::Device device = raster::Device::software;
  /// The longest one dispatch may take, and each step of compiling (glslang and spirv-cross as
  /// programs under a memory limit, shader_tools.h; the driver's compile in this process; at
  /// least kToolLeastSeconds). A GPU dispatch or a driver's compile cannot be cancelled: one that
  /// runs longer (a loop that does not end) is said on standard error and the process exits with
  /// status 2 (kHangExitStatus). A tool that runs longer is stopped and open() fails.
  double timeout_seconds = 10;
};

inline constexpr int kHangExitStatus = 2;

/// The inputs of one request as the wrapped shader reads them (kRequestVectors vec4): M', M'^-1,
/// M, M^-1 by rows, zparams, projection params, (ndc x, ndc y, depth, view axis),
/// (uv x, uv y, near, far), (frag coord x, y, target width, height) and (texel column, row,
/// texel width, height), the pixel's rows counted the way `v` runs. The inverses and the
/// parameters are computed in double from the float inputs and rounded to float, as an engine's
/// CPU code sets them; the pixel is its centre at a target's pixel (sample.pixel.at_centre), else
/// the sample's NDC.
std::array<float, kRequestVectors * 4> request_of(const oracle::DepthSample<float>& sample,
                                                  VDirection v = VDirection::up);

/// Whether a camera M is one the parameters read off a perspective camera (zparams, near, far,
/// projection params) describe: fourth row (0, 0, +-1, 0), no shear of z into x, y beyond M13,
/// M23, finite near and far in front of it.
bool perspective_along_z(Convention convention, const Matrix4<float>& m);

/// Whether open()'s error says the GPU path cannot run on this machine (no EGL, or HLSL's tools
/// missing: it names what to install), not that the user's shader is wrong.
bool cannot_run_here(const std::string& error);

class ShaderRunner {
 public:
  /// Reads, wraps and compiles each function for every convention (HLSL through glslang to
  /// SPIR-V and spirv-cross to GLSL). Fails with one line per problem: the file unreadable, the
  /// function or its parameters wrong (find_signature()), the compiler's log with its lines
  /// mapped to the user's file, the tools or EGL missing (saying what to install).
  static Expected<std::unique_ptr<ShaderRunner>> open(const std::vector<ShaderFunction>& functions,
                                                      const RunnerOptions& options = {});
  ~ShaderRunner();
  ShaderRunner(const ShaderRunner&) = delete;
  ShaderRunner& operator=(const ShaderRunner&) = delete;

  /// GL_RENDERER and GL_VERSION of the device the shaders run on.
  const std::string& renderer() const;
  const std::vector<ShaderFunction>& functions() const;
  /// Whether the function for `kind` takes an input read off a perspective camera.
  bool needs_perspective_camera(protocol::ConsumerKind kind) const;
  /// Whether it takes the pixel as a GPU hands it (uv, frag_coord, texel: is_pixel_position()).
  bool reads_pixel(protocol::ConsumerKind kind) const;
  /// Whether it takes a texel, which names a pixel (asked at pixel centres only).
  bool reads_texel(protocol::ConsumerKind kind) const;

  /// The `kind` function's answers for `samples`, in order: 3 numbers each for view_position, 1
  /// for linear_depth. Fails where the kind has no function or the driver reports an error.
  Expected<std::vector<std::vector<float>>> run(
      protocol::ConsumerKind kind, const std::vector<oracle::DepthSample<float>>& samples);

 private:
  struct State;
  explicit ShaderRunner(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

/// The runner's functions as an oblique::Consumers<float> (view_position and linear_depth, each
/// call one dispatch; a Failure-like std::runtime_error where the driver fails), judged with the
/// GPU's arithmetic and by the pixel as it was handed (oracle::PixelInput::gpu where a function
/// reads uv, frag_coord or texel), asking only the cameras the functions' inputs describe, at
/// `sampling`'s positions (pixel centres where a function reads a texel). `runner` must outlive
/// it.
Consumers<float> shader_consumers(ShaderRunner& runner, const std::string& name,
                                  oracle::Sampling sampling = oracle::Sampling::pixels);

/// `asks` (view_position and linear_depth asks of a consumer round) answered in one dispatch per
/// kind: their samples taken by calling each ask on a recording Consumers.
Expected<std::vector<std::vector<float>>> answer_asks(
    ShaderRunner& runner, const std::vector<const oracle::ConsumerAsk<float>*>& asks);

}  // namespace oblique::shader
