// check_shader() (oblique/testing/shader.h): the shader's function opened on the GPU path and
// checked as any Consumers<float> is (check_consumers()).
#include "oblique/testing/shader.h"

#include "oblique/protocol/shell_text.h"
#include "oblique/shader/shader_runner.h"

namespace oblique::testing {

void check_shader(const std::string& path, const std::string& function, const Contract& contract,
                  const ShaderSettings& settings) {
  const Expected<shader::ShaderFunction> found =
      shader::shader_function_in(path, function, std::nullopt, settings.defines,
                                 settings.timeout_seconds, settings.v, settings.vectors);
  if (!found) {
    if (shader::cannot_run_here(found.error()))
      GTEST_SKIP() << "oblique::testing: the GPU path cannot run here: "
                   << protocol::escape_bytes(found.error());
    ADD_FAILURE() << "oblique::testing: " << protocol::escape_bytes(found.error());
    return;
  }
  shader::RunnerOptions options;
  options.device = settings.device;
  options.timeout_seconds = settings.timeout_seconds;
  const Expected<std::unique_ptr<shader::ShaderRunner>> runner =
      shader::ShaderRunner::open({*found}, options);
  if (!runner) {
    if (shader::cannot_run_here(runner.error()))
      GTEST_SKIP() << "oblique::testing: the GPU path cannot run here: "
                   << protocol::escape_bytes(runner.error());
    ADD_FAILURE() << "oblique::testing: " << protocol::escape_bytes(runner.error());
    return;
  }
  check_consumers(shader::shader_consumers(**runner, path + ":" + function, settings.sampling),
                  contract);
}

}  // namespace oblique::testing
