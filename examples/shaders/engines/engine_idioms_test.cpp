// The engine idioms (idioms.txt, docs/shaders.md) through OBLIQUE_SHADER_TEST_WITH, as an engine's
// test suite would declare them: each right function under the conventions and families it
// claims and the way its v runs; each wrong twin alone (CTest runs one at a time) is caught and
// named. OBLIQUE_ENGINE_IDIOMS is this folder.
#include <oblique/testing/shader.h>

#include <string>
#include <vector>

namespace {

std::string idiom(const char* file) {
  return std::string(OBLIQUE_ENGINE_IDIOMS) + "/" + file;
}

/// What a function claims: its conventions, and its families (empty: every one).
oblique::Contract claims(std::vector<oblique::Convention> conventions,
                         std::vector<oblique::cases::Family> families = {}) {
  oblique::Contract c;
  c.conventions = std::move(conventions);
  c.families = std::move(families);
  return c;
}

const std::vector<oblique::Convention> every = {
    oblique::Convention::gl, oblique::Convention::zero_one, oblique::Convention::reversed_z};
const std::vector<oblique::Convention> zero_one_and_reversed = {oblique::Convention::zero_one,
                                                                oblique::Convention::reversed_z};
/// The cameras projection parameters describe (perspective along z).
const std::vector<oblique::cases::Family> along_z = {
    oblique::cases::Family::perspective, oblique::cases::Family::off_axis,
    oblique::cases::Family::infinite,    oblique::cases::Family::y_flipped,
    oblique::cases::Family::jittered,    oblique::cases::Family::x_flipped,
    oblique::cases::Family::xy_flipped,  oblique::cases::Family::left_handed};

oblique::testing::ShaderSettings v(oblique::shader::VDirection direction) {
  oblique::testing::ShaderSettings s;
  s.v = direction;
  return s;
}

/// A Direct3D engine's settings: v down (HLSL's default) and row vectors.
oblique::testing::ShaderSettings row_vectors() {
  oblique::testing::ShaderSettings s;
  s.vectors = oblique::shader::Vectors::row;
  return s;
}

}  // namespace

// Each idiom's files are FILE.EXT and FILE_wrong.EXT: the macro takes the stem and the extension.
#define OBLIQUE_IDIOM_FILES(Name, stem, ext, kind, contract, settings)                       \
  OBLIQUE_SHADER_TEST_WITH(RightIdioms, Name, idiom(stem "." ext), kind, contract, settings) \
  OBLIQUE_SHADER_TEST_WITH(WrongIdioms, Name, idiom(stem "_wrong." ext), kind, contract, settings)

const oblique::testing::ShaderSettings by_language{};

OBLIQUE_IDIOM_FILES(gl_uv, "gl_uv_view_position", "glsl", "view_position", claims(every),
                    by_language)
OBLIQUE_IDIOM_FILES(gl_uv_linear, "gl_uv_linear_depth", "glsl", "linear_depth", claims(every),
                    by_language)
OBLIQUE_IDIOM_FILES(d3d_uv, "d3d_uv_view_position", "hlsl", "view_position", claims(every),
                    by_language)
OBLIQUE_IDIOM_FILES(d3d_sv_position, "d3d_sv_position_texel_size", "hlsl", "view_position",
                    claims(every), by_language)
OBLIQUE_IDIOM_FILES(gl_frag_coord, "gl_frag_coord_resolution", "glsl", "view_position",
                    claims(every), by_language)
OBLIQUE_IDIOM_FILES(gl_viewport, "gl_frag_coord_viewport", "glsl", "view_position", claims(every),
                    by_language)
OBLIQUE_IDIOM_FILES(gl_texel_fetch, "gl_texel_fetch", "glsl", "view_position", claims(every),
                    by_language)
OBLIQUE_IDIOM_FILES(d3d_load_texel, "d3d_load_texel_linear_depth", "hlsl", "linear_depth",
                    claims(every), by_language)
OBLIQUE_IDIOM_FILES(d3d_reversed_z, "d3d_reversed_z_mad", "hlsl", "view_position",
                    claims(zero_one_and_reversed), by_language)
OBLIQUE_IDIOM_FILES(vulkan_uv, "vulkan_screen_uv", "glsl", "view_position",
                    claims(zero_one_and_reversed), by_language)
OBLIQUE_IDIOM_FILES(cross_api_v_down, "cross_api_uv", "glsl", "view_position", claims(every),
                    v(oblique::shader::VDirection::down))
OBLIQUE_IDIOM_FILES(cross_api_v_up, "cross_api_uv", "glsl", "view_position", claims(every),
                    v(oblique::shader::VDirection::up))
OBLIQUE_IDIOM_FILES(gl_view_ray, "gl_projection_params_view_ray", "glsl", "view_position",
                    claims(every, along_z), by_language)
OBLIQUE_IDIOM_FILES(d3d_row_vectors, "d3d_row_vectors", "hlsl", "view_position", claims(every),
                    row_vectors())
OBLIQUE_IDIOM_FILES(gl_world, "gl_inverse_view_projection_world", "glsl", "world_position",
                    claims(every), by_language)
OBLIQUE_IDIOM_FILES(d3d_world_row_vectors, "d3d_world_position_row_vectors", "hlsl",
                    "world_position", claims(every), row_vectors())
