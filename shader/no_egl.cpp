// A build without EGL and OpenGL: the shader runner says what to install.
#include <stdexcept>

#include "oblique/shader/shader_runner.h"

namespace oblique::shader {

struct ShaderRunner::State {};

ShaderRunner::ShaderRunner(std::unique_ptr<State> state) : state_(std::move(state)) {}
ShaderRunner::~ShaderRunner() = default;

Expected<std::unique_ptr<ShaderRunner>> ShaderRunner::open(const std::vector<ShaderFunction>&,
                                                           const RunnerOptions&) {
  return Expected<std::unique_ptr<ShaderRunner>>::failure(
      "no EGL: this oblique was built without EGL and OpenGL, which shaders run on; install "
      "libegl-dev libgl-dev libopengl-dev libegl-mesa0 libgl1-mesa-dri (bash scripts/setup.sh) "
      "and build again");
}

bool cannot_run_here(const std::string& error) {
  return error.rfind("no EGL", 0) == 0 || error.find("which is not installed") != std::string::npos;
}

const std::string& ShaderRunner::renderer() const {
  static const std::string none;
  return none;
}
const std::vector<ShaderFunction>& ShaderRunner::functions() const {
  static const std::vector<ShaderFunction> none;
  return none;
}
bool ShaderRunner::needs_perspective_camera(protocol::ConsumerKind) const {
  return false;
}
bool ShaderRunner::reads_pixel(protocol::ConsumerKind) const {
  return false;
}
bool ShaderRunner::reads_texel(protocol::ConsumerKind) const {
  return false;
}
Expected<std::vector<std::vector<float>>> ShaderRunner::run(
    protocol::ConsumerKind, const std::vector<oracle::DepthSample<float>>&) {
  return Expected<std::vector<std::vector<float>>>::failure("no EGL in this build");
}
Consumers<float> shader_consumers(ShaderRunner&, const std::string& name, oracle::Sampling) {
  Consumers<float> out;
  out.name = name;
  return out;
}
Expected<std::vector<std::vector<float>>> answer_asks(
    ShaderRunner&, const std::vector<const oracle::ConsumerAsk<float>*>&) {
  return Expected<std::vector<std::vector<float>>>::failure("no EGL in this build");
}

}  // namespace oblique::shader
