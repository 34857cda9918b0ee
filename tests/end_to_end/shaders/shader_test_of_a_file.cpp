// OBLIQUE_SHADER_TEST_WITH as a user's test binary has it, on the shader the environment names
// (the hostile files of tests/end_to_end/shaders.cmake are tried through it as through verify and
// check): OBLIQUE_TRIED_SHADER=FILE:FUNCTION, OBLIQUE_TRIED_DEFINES=NAME[=VALUE],... and
// OBLIQUE_TRIED_TIMEOUT (seconds).
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "oblique/testing/shader.h"

namespace {

std::string env(const char* name) {
  const char* value = std::getenv(name);
  return value ? value : "";
}

std::string tried_file() {
  const std::string spec = env("OBLIQUE_TRIED_SHADER");
  return spec.substr(0, spec.rfind(':'));
}

std::string tried_function() {
  const std::string spec = env("OBLIQUE_TRIED_SHADER");
  return spec.substr(spec.rfind(':') + 1);
}

oblique::testing::ShaderSettings tried_settings() {
  oblique::testing::ShaderSettings settings;
  std::istringstream defines(env("OBLIQUE_TRIED_DEFINES"));
  for (std::string d; std::getline(defines, d, ',');)
    if (!d.empty()) settings.defines.push_back(d);
  if (!env("OBLIQUE_TRIED_TIMEOUT").empty())
    settings.timeout_seconds = std::strtod(env("OBLIQUE_TRIED_TIMEOUT").c_str(), nullptr);
  return settings;
}

}  // namespace

OBLIQUE_SHADER_TEST_WITH(TriedShader, holdsEveryConsumerProperty, tried_file(), tried_function(),
                         oblique::Contract{}, tried_settings())
