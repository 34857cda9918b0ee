// The shader-source scanner (shader_scanner.h): definitions found in one pass over the tokens,
// the #version line, and what a depth function must not declare; files of 16 MiB of one
// identifier, of comments and of parameters read without recursion (std::regex overflowed the
// stack at about 50 KB).
#include <gtest/gtest.h>

#include <string>

#include "oblique/shader/shader_function.h"
#include "oblique/shader/shader_scanner.h"

namespace oblique::shader {
namespace {

using protocol::ConsumerKind;

constexpr std::size_t kSixteenMiB = std::size_t{16} << 20;
const std::string kRight =
    "vec3 view_position(mat4 inverse_projection, vec2 ndc, float depth) { return vec3(0.0); }\n";

TEST(ShaderScanner, definitionsAreFoundWithTheirParametersAndLines) {
  const std::string text = without_comments(
      "#define F(x) vec3 g(x) {\n"  // a preprocessor line is no definition
      "float helper(float x) { if (x > 0.0) { return x; } return 0.0; }\n"
      "/* vec3 hidden(float d) { } */\n"
      "float3 hlsl(float depth : DEPTH, float2 uv) : SV_Target {\n"
      "}\n");
  const std::vector<Token> t = tokens(text);
  const std::vector<Definition> d = definitions(t);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d[0].name, "helper");
  EXPECT_EQ(d[0].line, 2);
  EXPECT_EQ(d[1].name, "hlsl");
  EXPECT_EQ(d[1].return_type, "float3");
  EXPECT_EQ(d[1].line, 4);
  EXPECT_EQ(d[1].parameters.size(), 7u);  // float depth : DEPTH , float2 uv
}

TEST(ShaderScanner, theVersionLineIsTheDirectiveOnly) {
  const std::string text = "// #version 100\n  #  version 450 core\nvoid f() {}\n";
  const auto v = version_line(text);
  ASSERT_TRUE(v);
  EXPECT_EQ(text.substr(v->first, v->second), "  #  version 450 core");
  EXPECT_FALSE(version_line("#versions 1\n#define version 2\n"));
}

TEST(ShaderScanner, whatReachesBeyondAFunctionsInputsIsNamed) {
  auto beyond = [](const std::string& source) {
    const auto b = reaches_beyond_its_inputs(tokens(without_comments(source)));
    return b ? *b : std::string("(none)");
  };
  EXPECT_EQ(beyond(kRight), "(none)");
  EXPECT_EQ(beyond("float image_depth; float images2; float WaveHeight; float subgroupish;"),
            "line 1: subgroupish reads other lanes' values (a subgroup or wave operation)");
  EXPECT_EQ(beyond("float image_depth; float WaveHeight;"), "(none)");
  EXPECT_NE(beyond("\nlayout(std430, binding = 1) buffer B { vec4 a[]; };")
                .find("line 2: buffer declares a storage block"),
            std::string::npos);
  EXPECT_NE(beyond("layout(rgba32f) uniform image2D img;").find("image2D declares an image"),
            std::string::npos);
  EXPECT_NE(beyond("shared vec4 s[64];").find("memory shared between invocations"),
            std::string::npos);
  EXPECT_NE(beyond("groupshared float4 s[64];").find("memory shared between invocations"),
            std::string::npos);
  EXPECT_NE(beyond("RWStructuredBuffer<float4> a;").find("read-write resource"), std::string::npos);
  EXPECT_NE(beyond("uint i = gl_GlobalInvocationID.x;").find("which invocation it is"),
            std::string::npos);
  EXPECT_NE(beyond("float x = WaveReadLaneAt(d, 1);").find("other lanes"), std::string::npos);
}

// Each file is 16 MiB; each is answered (found, or refused in a line) with no recursion that
// grows with it. (No time is asserted: the CTest's timeout stands for "in seconds".)
TEST(ShaderScanner, sixteenMebibytesOfOneIdentifierAreRead) {
  const std::string source = "float " + std::string(kSixteenMiB, 'a') + ";\n" + kRight;
  const Expected<Signature> s =
      find_signature(source, "view_position", Language::glsl, ConsumerKind::view_position);
  ASSERT_TRUE(s) << s.error().substr(0, 200);
  EXPECT_EQ(s->line, 2);
}

TEST(ShaderScanner, sixteenMebibytesOfCommentsAreRead) {
  std::string source = "#version 450 core\n";
  while (source.size() < kSixteenMiB) source += "// a comment line as a licence has it\n";
  source += "/*" + std::string(1 << 20, '*') + "*/\n" + kRight;
  const Expected<Signature> s =
      find_signature(source, "view_position", Language::glsl, ConsumerKind::view_position);
  ASSERT_TRUE(s) << s.error().substr(0, 200);
  EXPECT_EQ(s->parameters.size(), 3u);
}

TEST(ShaderScanner, sixteenMebibytesOfParametersAreRead) {
  std::string source = "vec3 view_position(mat4 inverse_projection";
  while (source.size() < kSixteenMiB) source += ", float depth";
  source += ") { return vec3(0.0); }\n";
  const Expected<Signature> s =
      find_signature(source, "view_position", Language::glsl, ConsumerKind::view_position);
  // Every parameter is a known input: found, with its 1.2 million parameters bound.
  ASSERT_TRUE(s) << s.error().substr(0, 200);
  EXPECT_GT(s->parameters.size(), 1000000u);
  std::string unknown = "vec3 view_position(float depth";
  while (unknown.size() < kSixteenMiB) unknown += ", float extra";
  unknown += ") { }\n";
  const Expected<Signature> u =
      find_signature(unknown, "view_position", Language::glsl, ConsumerKind::view_position);
  ASSERT_FALSE(u);
  EXPECT_NE(u.error().find("parameter extra is not an input the harness knows"), std::string::npos);
}

TEST(ShaderScanner, manyDefinitionsAreListedInShort) {
  std::string source;
  for (int i = 0; i < 200000; ++i) source += "float f" + std::to_string(i) + "(float x) { }\n";
  const Expected<Signature> s =
      find_signature(source, "view_position", Language::glsl, ConsumerKind::view_position);
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().find("f19 and 199980 more"), std::string::npos) << s.error();
}

}  // namespace
}  // namespace oblique::shader
