// A user's depth function in a shader file (GLSL or HLSL) and the wrapper convention that binds
// the harness's inputs to its parameters by their names (docs/shaders.md): a function
//   vec3 view_position(mat4 inverse_projection, vec2 ndc, float depth)
// is given M'^-1, the pixel's NDC x and y and the depth as the shader samples it. Each name
// stands for one input, as engines name it (an inverse projection set on the CPU; _ZBufferParams
// computed from near and far; a projection-params vec4), so most users write no wrapper.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "oblique/expected.h"
#include "oblique/protocol/consumer_messages.h"
#include "oblique/util/enum_names.h"

namespace oblique::shader {

enum class Language { glsl, hlsl };

inline constexpr EnumName<Language> language_names[] = {
    {Language::glsl, "glsl"},
    {Language::hlsl, "hlsl"},
};
constexpr std::string_view language_name(Language l) noexcept {
  return name_in(language_names, l);
}
constexpr std::optional<Language> parse_language(std::string_view name) noexcept {
  return value_in(language_names, name);
}

/// What the harness gives a parameter (its name says which; the accepted names per input are
/// input_names()).
enum class Input {
  projection,                 ///< mat4: M', the matrix the depth was rendered with
  inverse_projection,         ///< mat4: M'^-1, set on the CPU (computed in double, rounded)
  camera_projection,          ///< mat4: M, the camera's matrix before the oblique modification
  camera_inverse_projection,  ///< mat4: M^-1
  zparams,                    ///< vec4: Unity's _ZBufferParams from M's near and far
  projection_params,          ///< vec4: (1 / M11, 1 / M22, M13, M23) of M
  ndc,                        ///< vec2: the pixel's NDC x and y
  uv,  ///< vec2: the pixel's texture coordinate, its centre's (x + 1/2) / size, v up or down
  frag_coord,   ///< vec2 or vec4: gl_FragCoord / SV_Position, the pixel's centre in pixels
  texel,        ///< ivec2: the pixel's column and row, as texelFetch and Load take them
  target_size,  ///< vec2: the render target's width and height in pixels
  viewport,     ///< vec4: (x, y, width, height) of the viewport: (0, 0, the target's size)
  texel_size,   ///< vec2: 1 / width and 1 / height, set on the CPU
  depth,        ///< float: the window depth as the shader samples it
  near_plane,   ///< float: M's near distance
  far_plane,    ///< float: M's far distance (inf for an infinite M)
  view_axis,    ///< float: -1 for a camera looking down -z, +1 down +z
  convention,   ///< int: OBLIQUE_CONVENTION (0 gl, 1 zero_one, 2 reversed_z)
  // The pass camera's view (world -> camera) and what engines derive from it, set on the CPU
  // (computed in double, rounded): for a world position, or a view position through world space.
  view,                     ///< mat4: V
  inverse_view,             ///< mat4: V^-1
  view_projection,          ///< mat4: M' V
  inverse_view_projection,  ///< mat4: (M' V)^-1
};

/// The names a parameter may have for `input` (matched ignoring case and underscores), the
/// first the documented one.
const std::vector<std::string_view>& input_names(Input input);
std::string_view input_name(Input input);
/// Whether `input` is read off M as a perspective camera (near, far, zparams, projection params):
/// a function that takes one is asked only about perspective cameras looking along z.
bool needs_perspective_camera(Input input);

/// Which way the texture coordinate v (and the rows of gl_FragCoord, SV_Position and texel
/// coordinates) runs against NDC y: up (v = (NDC y + 1) / 2, rows from the bottom: GL, and Vulkan,
/// whose NDC y already points down the image) or down (v = (1 - NDC y) / 2, rows from the top:
/// Direct3D, Metal). A shader sees it as OBLIQUE_UV_V_DOWN (0 or 1).
enum class VDirection { up, down };

inline constexpr EnumName<VDirection> v_direction_names[] = {
    {VDirection::up, "up"},
    {VDirection::down, "down"},
};
constexpr std::string_view v_direction_name(VDirection v) noexcept {
  return name_in(v_direction_names, v);
}
constexpr std::optional<VDirection> parse_v_direction(std::string_view name) noexcept {
  return value_in(v_direction_names, name);
}
/// The direction engines of `language` mostly use: GLSL up, HLSL down.
constexpr VDirection default_v_direction(Language language) noexcept {
  return language == Language::hlsl ? VDirection::down : VDirection::up;
}
/// How the engine's matrices multiply vectors: column vectors (M v: GLSL `M * v`, HLSL
/// `mul(M, v)`; the harness hands M) or row vectors (v M: HLSL `mul(v, M)`, DirectXMath and D3DX
/// style; the harness hands M^T, as such an engine's uniform holds it). A shader sees it as
/// OBLIQUE_ROW_VECTORS (0 or 1).
enum class Vectors { column, row };

inline constexpr EnumName<Vectors> vectors_names[] = {
    {Vectors::column, "column"},
    {Vectors::row, "row"},
};
constexpr std::string_view vectors_name(Vectors v) noexcept {
  return name_in(vectors_names, v);
}
constexpr std::optional<Vectors> parse_vectors(std::string_view name) noexcept {
  return value_in(vectors_names, name);
}

/// Whether `input` is the pixel as a GPU hands it (uv, frag_coord, texel): the function derives
/// NDC from it in its own arithmetic (oracle::PixelInput::gpu).
bool is_pixel_position(Input input);

struct Parameter {
  std::string type;  ///< as written (vec4, float4, ...)
  std::string name;
  Input input = Input::depth;
};

/// The function found in the user's file and its parameters bound.
struct Signature {
  std::string return_type;
  std::string name;
  std::vector<Parameter> parameters;
  int line = 0;  ///< where it is defined, from 1
};

/// Finds the definition of `function` in `source` (comments skipped; give it the text the
/// preprocessor keeps, preprocessed(), so that #if variants are chosen) and binds each parameter by
/// its name and type for a function of `kind` (view_position returns vec3 / float3, linear_depth
/// float). The error says what is wrong in the user's words: no such function (naming the ones
/// found), more than one, a return type or a parameter's type that does not fit, a parameter
/// name the convention does not know (listing the names it does).
Expected<Signature> find_signature(const std::string& source, const std::string& function,
                                   Language language, protocol::ConsumerKind kind);

/// A depth function to run: the file, the function's name, its language and the request kind it
/// answers.
struct ShaderFunction {
  std::string path;
  std::string function;
  Language language = Language::glsl;
  protocol::ConsumerKind kind = protocol::ConsumerKind::view_position;
  /// The engine's defines (NAME or NAME=VALUE, as -D takes them): the preprocessor keeps the
  /// #if variant they choose, beside OBLIQUE_CONVENTION.
  std::vector<std::string> defines;
  /// Which way v runs (uv, and the rows of frag_coord and texel).
  VDirection v = VDirection::up;
  /// How its matrices multiply vectors (the matrices handed: M, or M^T for row vectors).
  Vectors vectors = Vectors::column;
};

/// `--shader FILE[:FUNCTION]` split: the file, and the function ("" when none is named; the part
/// after the last ':' is a function only where it is an identifier, so paths may hold ':').
std::pair<std::string, std::string> split_shader_spec(const std::string& spec);

/// The functions `--shader FILE[:FUNCTION]` names for `kinds` (view_position, linear_depth):
/// FILE:FUNCTION answers the one kind given; FILE alone has a function named after each kind.
/// The language is `language` when given, else the file's extension's (.hlsl, .fx: HLSL; else
/// GLSL). The error says why not (another kind than the depth ones, a function named for
/// several kinds).
Expected<std::vector<ShaderFunction>> shader_functions(
    const std::string& spec, const std::vector<protocol::ConsumerKind>& kinds,
    std::optional<Language> language);

/// The text of a shader file: a regular file of at most kMaxShaderBytes. The error says why not
/// (missing, a folder or a device, too large, unreadable).
inline constexpr std::size_t kMaxShaderBytes = 16u << 20;
Expected<std::string> read_shader_file(const std::string& path);

/// The function `function` of the file `path` as a ShaderFunction: its kind from its return
/// type (vec3 / float3: view_position; float: linear_depth) in the variant the preprocessor keeps
/// under `defines` (preprocessed() within `seconds`), its language from `language` or the file's
/// extension, its v direction `v` or the language's default, its matrices' `vectors`. The error
/// says why not (the file unreadable, no such function, another return type, the preprocessor
/// stopped).
Expected<ShaderFunction> shader_function_in(const std::string& path, const std::string& function,
                                            std::optional<Language> language = std::nullopt,
                                            const std::vector<std::string>& defines = {},
                                            double seconds = 10,
                                            std::optional<VDirection> v = std::nullopt,
                                            Vectors vectors = Vectors::column);

/// The `#define` lines the wrapper and the preprocessor begin with: OBLIQUE_GL, OBLIQUE_ZERO_ONE,
/// OBLIQUE_REVERSED_Z, OBLIQUE_CONVENTION (`convention`), OBLIQUE_UV_V_DOWN (`v`),
/// OBLIQUE_ROW_VECTORS (`vectors`), then `user_defines` (define_lines()).
std::string convention_defines(int convention, VDirection v, const std::string& user_defines,
                               Vectors vectors = Vectors::column);

/// The compute shader that runs `signature` of the user's `source` on a batch of requests, in
/// the user's language: GLSL 4.50 (or HLSL for glslang), the user's file included with line
/// directives so that a compiler's message names the user's file and line. `convention` is
/// defined as OBLIQUE_CONVENTION, and `user_defines` (define_lines()) after it.
std::string wrapped_source(const std::string& source, const std::string& path,
                           const Signature& signature, Language language, int convention,
                           VDirection v, const std::string& user_defines = "",
                           Vectors vectors = Vectors::column);

/// The first line number of the GLSL wrapper's own code: a compiler's line below it is the
/// user's file's.
inline constexpr int kWrapperFirstLine = 100001;

/// A request's inputs as the wrapped shader reads them: kRequestVectors vec4 per request.
inline constexpr int kRequestVectors = 38;

}  // namespace oblique::shader
