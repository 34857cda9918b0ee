// The shader wrapper convention without a GPU (shader_function.h): a function found in its file
// and its parameters bound by name, the errors a user gets for a function that does not fit,
// `--shader FILE[:FUNCTION]` read, and the wrapped compute shader; and the GPU's bounds
// (tolerance.h kGpuLostBits) as the depth judges apply them.
#include <gtest/gtest.h>

#include <cmath>

#include "oblique/oblique.h"
#include "oblique/oracle/consumers.h"
#include "oblique/projection.h"
#include "oblique/references/depth_reconstruction.h"
#include "oblique/shader/shader_function.h"

namespace oblique::shader {
namespace {

using protocol::ConsumerKind;

TEST(ShaderFunction, parametersAreBoundByTheirNamesInEitherLanguage) {
  const std::string glsl = R"(
    // vec3 view_position(int nothing) { }   (a comment is no definition)
    float helper(float x) { return x; }
    vec3 view_position(mat4 InvProj, in vec2 ndc_xy, const float raw_depth, float view_axis) {
      return vec3(0.0);
    })";
  const Expected<Signature> g =
      find_signature(glsl, "view_position", Language::glsl, ConsumerKind::view_position);
  ASSERT_TRUE(g) << g.error();
  ASSERT_EQ(g->parameters.size(), 4u);
  EXPECT_EQ(g->parameters[0].input, Input::inverse_projection);
  EXPECT_EQ(g->parameters[1].input, Input::ndc);
  EXPECT_EQ(g->parameters[2].input, Input::depth);
  EXPECT_EQ(g->parameters[3].input, Input::view_axis);
  EXPECT_EQ(g->line, 4);
  const std::string hlsl = R"(
    float LinearDepth(float4 zBufferParams, float depth : DEPTH) { return 0; })";
  const Expected<Signature> h =
      find_signature(hlsl, "LinearDepth", Language::hlsl, ConsumerKind::linear_depth);
  ASSERT_TRUE(h) << h.error();
  EXPECT_EQ(h->parameters[0].input, Input::zparams);
  EXPECT_EQ(h->parameters[1].input, Input::depth);
}

TEST(ShaderFunction, aFunctionThatDoesNotFitIsRefusedInTheUsersWords) {
  auto error = [](const std::string& source, ConsumerKind kind, Language language) {
    const Expected<Signature> s = find_signature(source, "f", language, kind);
    return s ? std::string("(found)") : s.error();
  };
  const auto vp = ConsumerKind::view_position;
  EXPECT_NE(error("vec3 g(float depth) { }", vp, Language::glsl)
                .find("no function named f is defined (functions found: g)"),
            std::string::npos);
  EXPECT_NE(error("vec3 f(float depth) { } vec3 f(vec2 ndc) { }", vp, Language::glsl)
                .find("defined 2 times"),
            std::string::npos);
  EXPECT_NE(error("vec4 f(float depth) { }", vp, Language::glsl)
                .find("returns vec4; a view_position function returns vec3"),
            std::string::npos);
  EXPECT_NE(error("float4 f(float depth) { }", vp, Language::hlsl).find("returns float3"),
            std::string::npos);
  EXPECT_NE(error("vec3 f(mat4 lightViewProj) { }", vp, Language::glsl)
                .find("parameter lightViewProj is not an input the harness knows"),
            std::string::npos);
  EXPECT_NE(error("vec3 f(vec2 depth) { }", vp, Language::glsl)
                .find("parameter depth is vec2; the depth input is float"),
            std::string::npos);
  EXPECT_NE(error("vec3 f(out vec3 p, float depth) { }", vp, Language::glsl)
                .find("out and inout parameters are not part of the convention"),
            std::string::npos);
}

TEST(ShaderFunction, theSpecNamesAFileAndPerhapsAFunction) {
  EXPECT_EQ(split_shader_spec("a/b.glsl"), std::make_pair(std::string("a/b.glsl"), std::string()));
  EXPECT_EQ(split_shader_spec("a/b.glsl:ssr_depth"),
            std::make_pair(std::string("a/b.glsl"), std::string("ssr_depth")));
  EXPECT_EQ(split_shader_spec("C:/shaders/b.hlsl"),
            std::make_pair(std::string("C:/shaders/b.hlsl"), std::string()));
  EXPECT_EQ(split_shader_spec("b.glsl:12"),
            std::make_pair(std::string("b.glsl:12"), std::string()));
  const auto both = shader_functions(
      "d.hlsl", {ConsumerKind::view_position, ConsumerKind::linear_depth}, std::nullopt);
  ASSERT_TRUE(both) << both.error();
  ASSERT_EQ(both->size(), 2u);
  EXPECT_EQ((*both)[0].language, Language::hlsl);
  EXPECT_EQ((*both)[1].function, "linear_depth");
  EXPECT_FALSE(shader_functions(
      "d.glsl:f", {ConsumerKind::view_position, ConsumerKind::linear_depth}, std::nullopt));
  EXPECT_FALSE(shader_functions("d.glsl", {ConsumerKind::culling_planes}, std::nullopt));
}

TEST(ShaderFunction, theWrapperKeepsTheUsersLinesAndDefinesTheConvention) {
  const std::string user =
      "#version 330 core\nvec3 view_position(float depth) { return vec3(depth); }\n";
  const Expected<Signature> sig =
      find_signature(user, "view_position", Language::glsl, ConsumerKind::view_position);
  ASSERT_TRUE(sig) << sig.error();
  const std::string wrapped =
      wrapped_source(user, "u.glsl", *sig, Language::glsl, 2, VDirection::up);
  EXPECT_EQ(wrapped.rfind("#version 450 core\n", 0), 0u);
  EXPECT_EQ(wrapped.find("#version 330"), std::string::npos);  // the user's, taken out
  EXPECT_NE(wrapped.find("#define OBLIQUE_CONVENTION 2\n"), std::string::npos);
  // The user's file starts at line 1, its #version line kept as an empty one.
  EXPECT_NE(wrapped.find("#line 1\n\nvec3 view_position"), std::string::npos);
  EXPECT_NE(wrapped.find("view_position(oblique_requests[i].v[18].z)"), std::string::npos);
}

/// The smallest change of the right answer's z, as a power of 2 of its size, that the judge
/// rejects under `arithmetic`.
int first_rejected_exponent(const oracle::DepthSample<float>& s,
                            oracle::ConsumerArithmetic arithmetic) {
  const Vector3<float> right = view_position(s.projection, s.ndc_x, s.ndc_y, s.depth, s.convention);
  for (int e = 2; e < 40; ++e) {
    // From large changes to small ones: the last one rejected.
    const int k = 40 - e;
    Vector3<float> moved = right;
    moved.z() += std::ldexp(std::fabs(right.z()), -k);
    if (!oracle::judge_view_position(s, moved, arithmetic).holds) return k;
  }
  return 0;
}

TEST(GpuBounds, areTheCpuBoundsWithAUnitRoundoffThreeBitsCoarser) {
  // The GPU's arithmetic allows 2.5-ulp quotients: every operation within 2^3 u, so the least
  // change of an answer the judge rejects is 2^3 times the CPU's (one step of the exponent
  // search either way).
  const Matrix4<float> m = perspective<float>(1.0f, 1.25f, 0.5f, 200.0f, Convention::gl);
  const Vector4<float> c(0.3f, -0.8f, -0.5f, -2.0f);
  const ObliqueResult<float> r = apply<float>(m, c, Convention::gl);
  ASSERT_EQ(r.status, Status::ok);
  const auto s = oracle::depth_sample<float>(r.projection, m, Convention::gl, DepthBuffer::float32,
                                             Vector4<float>(0.1f, 0.2f, -5.0f, 1.0f));
  ASSERT_TRUE(s);
  const int cpu = first_rejected_exponent(*s, oracle::ConsumerArithmetic::ieee);
  const int gpu = first_rejected_exponent(*s, oracle::ConsumerArithmetic::gpu);
  ASSERT_GT(cpu, 0);
  EXPECT_GE(cpu - gpu, 2) << "cpu 2^-" << cpu << ", gpu 2^-" << gpu;
  EXPECT_LE(cpu - gpu, 4) << "cpu 2^-" << cpu << ", gpu 2^-" << gpu;
}

}  // namespace
}  // namespace oblique::shader
