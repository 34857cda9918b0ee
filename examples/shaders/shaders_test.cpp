// The bundled shaders through OBLIQUE_SHADER_TEST: the right ones pass in every convention; each
// wrong one alone (CTest runs one at a time, expect_consumer_caught.cmake) is caught by its
// property and named. OBLIQUE_SHADERS is this folder.
#include <oblique/testing/shader.h>

#include <string>

namespace {

std::string shader(const char* file) {
  return std::string(OBLIQUE_SHADERS) + "/" + file;
}

}  // namespace

OBLIQUE_SHADER_TEST(RightShaders, glslViewPosition, shader("depth_right.glsl"), "view_position",
                    oblique::Contract{})
OBLIQUE_SHADER_TEST(RightShaders, glslLinearDepth, shader("depth_right.glsl"), "linear_depth",
                    oblique::Contract{})
OBLIQUE_SHADER_TEST(RightShaders, glslInverseInShader, shader("depth_right_inverse_in_shader.glsl"),
                    "view_position", oblique::Contract{})
OBLIQUE_SHADER_TEST(RightShaders, hlslViewPosition, shader("depth_right.hlsl"), "view_position",
                    oblique::Contract{})
OBLIQUE_SHADER_TEST(RightShaders, hlslLinearDepth, shader("depth_right.hlsl"), "linear_depth",
                    oblique::Contract{})

#define OBLIQUE_WRONG_SHADERS(Language, file)                                                      \
  OBLIQUE_SHADER_TEST(WrongShaders, Language##CameraMatrix, shader(file),                          \
                      "camera_matrix_view_position", oblique::Contract{})                          \
  OBLIQUE_SHADER_TEST(WrongShaders, Language##Zparams, shader(file), "zparams_linear_depth",       \
                      oblique::Contract{})                                                         \
  OBLIQUE_SHADER_TEST(WrongShaders, Language##OpenglNdc, shader(file), "opengl_ndc_view_position", \
                      oblique::Contract{})                                                         \
  OBLIQUE_SHADER_TEST(WrongShaders, Language##ReversedAsForward, shader(file),                     \
                      "reversed_as_forward_view_position", oblique::Contract{})
OBLIQUE_WRONG_SHADERS(glsl, "depth_wrong.glsl")
OBLIQUE_WRONG_SHADERS(hlsl, "depth_wrong.hlsl")
