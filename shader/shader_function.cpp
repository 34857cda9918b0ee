// The wrapper convention (shader_function.h): a user's function found in its file, its
// parameters bound by name, and the compute shader that runs it on a batch.
#include "oblique/shader/shader_function.h"

#include "oblique/shader/shader_scanner.h"
#include "oblique/shader/shader_tools.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <unordered_set>

namespace oblique::shader {

namespace {

using protocol::ConsumerKind;

struct InputEntry {
  Input input;
  const char* glsl_type;
  std::vector<std::string_view> names;
  const char* other_type = nullptr;  ///< a second type it may have (frag_coord: vec4)
};

const std::vector<InputEntry>& inputs() {
  static const std::vector<InputEntry> table = {
      {Input::projection, "mat4", {"projection", "proj", "projection_matrix", "proj_matrix"}},
      {Input::inverse_projection,
       "mat4",
       {"inverse_projection", "inv_projection", "inv_proj", "inverse_proj", "inv_proj_matrix",
        "inverse_projection_matrix", "clip_to_view"}},
      {Input::camera_projection,
       "mat4",
       {"camera_projection", "camera_proj", "original_projection", "original"}},
      {Input::camera_inverse_projection,
       "mat4",
       {"camera_inverse_projection", "camera_inv_projection", "camera_inv_proj",
        "inv_camera_projection"}},
      {Input::zparams, "vec4", {"zparams", "zbuffer_params", "z_buffer_params"}},
      {Input::projection_params, "vec4", {"projection_params", "proj_params"}},
      {Input::ndc, "vec2", {"ndc", "ndc_xy", "clip_xy"}},
      {Input::uv,
       "vec2",
       {"uv", "texcoord", "screen_uv", "tex_coord", "texcoords", "screen_pos", "uv0"}},
      {Input::frag_coord,
       "vec2",
       {"frag_coord", "fragcoord", "sv_position", "position_ss", "position_cs", "pixel_position",
        "screen_position"},
       "vec4"},
      {Input::texel,
       "ivec2",
       {"texel", "texel_coord", "pixel_coord", "pixel", "texel_position", "dispatch_id"}},
      {Input::target_size,
       "vec2",
       {"target_size", "screen_size", "resolution", "viewport_size", "render_size", "buffer_size",
        "texture_size"}},
      {Input::viewport, "vec4", {"viewport", "viewport_rect", "view_rect"}},
      {Input::texel_size,
       "vec2",
       {"texel_size", "inv_screen_size", "inverse_screen_size", "rcp_screen_size", "pixel_size",
        "inv_resolution", "inv_viewport_size"}},
      {Input::depth, "float", {"depth", "raw_depth", "device_depth", "depth_sample", "d"}},
      {Input::near_plane, "float", {"near", "near_plane", "z_near"}},
      {Input::far_plane, "float", {"far", "far_plane", "z_far"}},
      {Input::view_axis, "float", {"view_axis", "axis"}},
      {Input::convention, "int", {"convention"}},
      {Input::view, "mat4", {"view", "view_matrix", "world_to_view", "world_to_camera"}},
      {Input::inverse_view,
       "mat4",
       {"inverse_view", "inv_view", "inverse_view_matrix", "inv_view_matrix", "view_to_world",
        "camera_to_world"}},
      {Input::view_projection,
       "mat4",
       {"view_projection", "view_proj", "view_projection_matrix", "view_proj_matrix",
        "world_to_clip"}},
      {Input::inverse_view_projection,
       "mat4",
       {"inverse_view_projection", "inv_view_projection", "inv_view_proj", "inverse_view_proj",
        "inv_view_proj_matrix", "inverse_view_projection_matrix", "clip_to_world"}},
  };
  return table;
}

const InputEntry& entry(Input input) {
  for (const InputEntry& e : inputs())
    if (e.input == input) return e;
  return inputs().front();
}

std::string folded(std::string_view name) {
  std::string out;
  for (const char ch : name)
    if (ch != '_') out += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return out;
}

/// An HLSL type in GLSL's words (float4x4 -> mat4, float3 -> vec3); GLSL's as written.
std::string glsl_type(const std::string& type) {
  static const std::map<std::string, std::string> hlsl = {
      {"float4x4", "mat4"}, {"float4", "vec4"}, {"float3", "vec3"}, {"float2", "vec2"},
      {"float", "float"},   {"int", "int"},     {"int2", "ivec2"}};
  const auto it = hlsl.find(type);
  return it == hlsl.end() ? type : it->second;
}

/// The type as the user's language writes it.
std::string type_in(const std::string& glsl, Language language) {
  if (language == Language::glsl) return glsl;
  static const std::map<std::string, std::string> names = {
      {"mat4", "float4x4"}, {"vec4", "float4"}, {"vec3", "float3"}, {"vec2", "float2"},
      {"float", "float"},   {"int", "int"},     {"ivec2", "int2"}};
  return names.at(glsl);
}

/// The input a parameter's name stands for (ignoring case and underscores), if any.
std::optional<Input> input_named(const std::string& name) {
  static const std::map<std::string, Input> by_folded_name = [] {
    std::map<std::string, Input> out;
    for (const InputEntry& e : inputs())
      for (const std::string_view n : e.names) out.emplace(folded(n), e.input);
    return out;
  }();
  const auto it = by_folded_name.find(folded(name));
  if (it == by_folded_name.end()) return std::nullopt;
  return it->second;
}

std::string names_list(const std::vector<std::string>& names) {
  constexpr std::size_t kShown = 20;
  std::string out;
  for (std::size_t k = 0; k < names.size() && k < kShown; ++k)
    out += (out.empty() ? "" : ", ") + names[k];
  if (names.size() > kShown) out += " and " + std::to_string(names.size() - kShown) + " more";
  return out.empty() ? "none" : out;
}

std::string_view kind_return(ConsumerKind kind) {
  return kind == ConsumerKind::linear_depth ? "float" : "vec3";
}

}  // namespace

const std::vector<std::string_view>& input_names(Input input) {
  return entry(input).names;
}

std::string_view input_name(Input input) {
  return entry(input).names.front();
}

bool is_pixel_position(Input input) {
  return input == Input::uv || input == Input::frag_coord || input == Input::texel;
}

bool needs_perspective_camera(Input input) {
  return input == Input::zparams || input == Input::projection_params ||
         input == Input::near_plane || input == Input::far_plane;
}

Expected<Signature> find_signature(const std::string& source, const std::string& function,
                                   Language language, ConsumerKind kind) {
  using Found = Expected<Signature>;
  const std::string text = without_comments(source);
  const std::vector<Definition> found = definitions(tokens(text));
  std::vector<std::string> found_names;  // in order, each once
  std::unordered_set<std::string_view> seen;
  std::vector<const Definition*> matches;
  for (const Definition& d : found) {
    if (d.name == function)
      matches.push_back(&d);
    else if (seen.insert(d.name).second)
      found_names.emplace_back(d.name.substr(0, 64));
  }
  if (matches.empty())
    return Found::failure("no function named " + function +
                          " is defined (functions found: " + names_list(found_names) + ")");
  if (matches.size() > 1)
    return Found::failure("function " + function + " is defined " + std::to_string(matches.size()) +
                          " times (overloads, or #if variants the defines leave both of): name "
                          "the one to run, or give the engine's defines (--define)");
  const Definition& m = *matches.front();
  Signature sig;
  sig.name = function;
  sig.return_type = std::string(m.return_type.substr(0, 64));
  sig.line = m.line;
  const std::string where = function + " (line " + std::to_string(sig.line) + ")";
  if (glsl_type(sig.return_type) != kind_return(kind))
    return Found::failure(where + " returns " + sig.return_type + "; a " +
                          std::string(protocol::consumer_kind_name(kind)) + " function returns " +
                          type_in(std::string(kind_return(kind)), language));
  // The parameters: pieces between commas, an HLSL semantic (": NAME") left out.
  std::vector<std::vector<Token>> pieces(1);
  for (const Token& t : m.parameters) {
    if (t.kind == Token::Kind::punctuation && t.text == ",")
      pieces.emplace_back();
    else
      pieces.back().push_back(t);
  }
  for (std::vector<Token>& piece : pieces) {
    std::string written;
    for (std::size_t k = 0; k < piece.size(); ++k) {
      if (piece[k].kind == Token::Kind::punctuation && piece[k].text == ":") {
        piece.resize(k);
        break;
      }
      if (written.size() < 80) written += (written.empty() ? "" : " ") + std::string(piece[k].text);
    }
    if (written.size() > 80) written = written.substr(0, 80) + "...";
    if (piece.empty() || (piece.size() == 1 && piece[0].text == "void")) continue;
    std::vector<std::string> words;
    bool only_words = true;
    for (const Token& t : piece) {
      static const std::vector<std::string_view> qualifiers = {
          "in",      "const",   "highp",     "mediump",     "lowp",
          "precise", "uniform", "row_major", "column_major"};
      only_words = only_words && t.kind == Token::Kind::identifier;
      if (std::find(qualifiers.begin(), qualifiers.end(), t.text) == qualifiers.end())
        words.emplace_back(t.text.substr(0, 64));
    }
    if (!only_words || words.size() != 2)
      return Found::failure(where + ": parameter \"" + written +
                            "\" is not a type and a name (out and inout parameters are not "
                            "part of the convention: return the answer)");
    Parameter p{words[0], words[1], Input::depth};
    const std::optional<Input> input = input_named(p.name);
    const bool known = input.has_value();
    if (known) p.input = *input;
    if (!known) {
      std::string vocabulary;
      for (const InputEntry& e : inputs())
        vocabulary += (vocabulary.empty() ? "" : "; ") + std::string(e.names.front()) + " (" +
                      type_in(e.glsl_type, language) + ")";
      return Found::failure(where + ": parameter " + p.name +
                            " is not an input the harness knows; name each parameter for what it "
                            "takes: " +
                            vocabulary + " (docs/shaders.md lists the other names of each)");
    }
    const InputEntry& e = entry(p.input);
    if (glsl_type(p.type) != e.glsl_type && !(e.other_type && glsl_type(p.type) == e.other_type))
      return Found::failure(where + ": parameter " + p.name + " is " + p.type + "; the " +
                            std::string(input_name(p.input)) + " input is " +
                            type_in(e.glsl_type, language) +
                            (e.other_type ? " or " + type_in(e.other_type, language) : ""));
    sig.parameters.push_back(p);
  }
  return sig;
}

Expected<std::string> read_shader_file(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status))
    return Expected<std::string>::failure("cannot read the shader " + path + ": no such file");
  if (!fs::is_regular_file(status))
    return Expected<std::string>::failure("cannot read the shader " + path +
                                          ": not a regular file (a folder, a device or a pipe)");
  const auto size = fs::file_size(path, ec);
  if (ec || size > kMaxShaderBytes)
    return Expected<std::string>::failure("cannot read the shader " + path + ": larger than " +
                                          std::to_string(kMaxShaderBytes >> 20) + " MiB");
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  if (in) text << in.rdbuf();
  if (!in) return Expected<std::string>::failure("cannot read the shader " + path);
  return text.str();
}

std::pair<std::string, std::string> split_shader_spec(const std::string& spec) {
  const auto colon = spec.rfind(':');
  if (colon == std::string::npos) return {spec, ""};
  const std::string tail = spec.substr(colon + 1);
  const bool identifier = !tail.empty() && !std::isdigit(static_cast<unsigned char>(tail[0])) &&
                          std::all_of(tail.begin(), tail.end(), [](char ch) {
                            return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_';
                          });
  if (!identifier) return {spec, ""};
  return {spec.substr(0, colon), tail};
}

Expected<ShaderFunction> shader_function_in(const std::string& path, const std::string& function,
                                            std::optional<Language> language,
                                            const std::vector<std::string>& defines, double seconds,
                                            std::optional<VDirection> v, Vectors vectors) {
  using Found = Expected<ShaderFunction>;
  const Expected<std::vector<ShaderFunction>> named =
      shader_functions(path + ":" + function, {ConsumerKind::view_position}, language);
  if (!named) return Found::failure(named.error());
  ShaderFunction f = named->front();
  f.defines = defines;
  if (v) f.v = *v;
  f.vectors = vectors;
  const Expected<std::string> text = read_shader_file(path);
  if (!text) return Found::failure(text.error());
  const Expected<std::string> user = define_lines(defines);
  if (!user) return Found::failure(user.error());
  const Expected<std::string> kept =
      preprocessed(*text, path, f.language, convention_defines(0, f.v, *user, f.vectors), seconds);
  if (!kept) return Found::failure(path + ": " + kept.error());
  // The return type decides the kind (a vec3 whose name says world is a world position):
  // find the function as either and keep the one that fits.
  for (const ConsumerKind kind : {ConsumerKind::view_position, ConsumerKind::linear_depth}) {
    const Expected<Signature> sig = find_signature(*kept, function, f.language, kind);
    if (sig) {
      f.kind = kind;
      if (kind == ConsumerKind::view_position &&
          folded(function).find("world") != std::string::npos)
        f.kind = ConsumerKind::world_position;
      return f;
    }
    if (sig.error().find(" returns ") == std::string::npos)
      return Found::failure(path + ": " + sig.error());
  }
  return Found::failure(path + ": " + function +
                        " returns neither a view or world position (vec3 / float3) nor a linear "
                        "depth (float)");
}

Expected<std::vector<ShaderFunction>> shader_functions(const std::string& spec,
                                                       const std::vector<ConsumerKind>& kinds,
                                                       std::optional<Language> language) {
  using Functions = Expected<std::vector<ShaderFunction>>;
  for (const ConsumerKind k : kinds) {
    if (k != ConsumerKind::view_position && k != ConsumerKind::linear_depth &&
        k != ConsumerKind::world_position)
      return Functions::failure(
          "a shader answers view_position, linear_depth and world_position; " +
          std::string(protocol::consumer_kind_name(k)) + " is asked of a program (--impl)");
  }
  if (kinds.empty()) return Functions::failure("--consumers names no request kind");
  const auto [path, function] = split_shader_spec(spec);
  if (path.empty()) return Functions::failure("--shader names no file");
  if (!function.empty() && kinds.size() > 1)
    return Functions::failure("one function (" + function + ") for " +
                              std::to_string(kinds.size()) +
                              " request kinds; give the file alone, with a function named after "
                              "each kind (view_position, linear_depth, world_position), or ask "
                              "one kind");
  Language lang = Language::glsl;
  if (language) {
    lang = *language;
  } else {
    const auto dot = path.rfind('.');
    const std::string ext = dot == std::string::npos ? "" : folded(path.substr(dot));
    if (ext == ".hlsl" || ext == ".fx" || ext == ".hlsli") lang = Language::hlsl;
  }
  std::vector<ShaderFunction> out;
  for (const ConsumerKind k : kinds)
    out.push_back({path,
                   function.empty() ? std::string(protocol::consumer_kind_name(k)) : function,
                   lang,
                   k,
                   {},
                   default_v_direction(lang)});
  return out;
}

std::string convention_defines(int convention, VDirection v, const std::string& user_defines,
                               Vectors vectors) {
  return "#define OBLIQUE_GL 0\n#define OBLIQUE_ZERO_ONE 1\n#define OBLIQUE_REVERSED_Z 2\n"
         "#define OBLIQUE_CONVENTION " +
         std::to_string(convention) + "\n#define OBLIQUE_UV_V_DOWN " +
         (v == VDirection::down ? "1" : "0") + "\n#define OBLIQUE_ROW_VECTORS " +
         (vectors == Vectors::row ? "1" : "0") + "\n" + user_defines;
}

std::string wrapped_source(const std::string& source, const std::string& path,
                           const Signature& signature, Language language, int convention,
                           VDirection v, const std::string& user_defines, Vectors vectors) {
  const bool glsl = language == Language::glsl;
  std::string user = source;
  if (glsl) {
    // The user's own #version line is ours to give (compute, 4.50): kept as an empty line.
    if (const auto v = version_line(user)) user.erase(v->first, v->second);
  }
  std::string out = glsl ? "#version 450 core\n" : "";
  out += convention_defines(convention, v, user_defines, vectors);
  const bool row = vectors == Vectors::row;
  // The user's lines keep their numbers; the wrapper's start at kWrapperFirstLine (drivers do
  // not all report #line's source-string number; shader_runner.cpp maps lines back). glslang's
  // HLSL takes a file name.
  std::string quoted;
  for (const char ch : path) quoted += (ch == '"' || ch == '\\') ? '_' : ch;
  out += glsl ? "#line 1\n" : "#line 1 \"" + quoted + "\"\n";
  out += user;
  out += glsl ? "\n#line " + std::to_string(kWrapperFirstLine) + "\n"
              : "\n#line 1 \"oblique-wrapper\"\n";
  auto argument = [&](const Parameter& p) -> std::string {
    const std::string v = "oblique_requests[i].v";
    switch (p.input) {
      case Input::projection: return "oblique_matrix(i, 0)";
      case Input::inverse_projection: return "oblique_matrix(i, 4)";
      case Input::camera_projection: return "oblique_matrix(i, 8)";
      case Input::camera_inverse_projection: return "oblique_matrix(i, 12)";
      case Input::zparams: return v + "[16]";
      case Input::projection_params: return v + "[17]";
      case Input::ndc: return v + "[18].xy";
      case Input::depth: return v + "[18].z";
      case Input::view_axis: return v + "[18].w";
      case Input::uv: return v + "[19].xy";
      case Input::frag_coord:
        if (glsl_type(p.type) == "vec4")
          return (glsl ? "vec4(" : "float4(") + v + "[20].xy, 0.0, 1.0)";
        return v + "[20].xy";
      case Input::target_size: return v + "[20].zw";
      case Input::viewport:
        return (glsl ? "vec4(0.0, 0.0, " : "float4(0.0, 0.0, ") + v + "[20].zw)";
      case Input::texel: return (glsl ? "ivec2(" : "int2(") + v + "[21].xy)";
      case Input::texel_size: return v + "[21].zw";
      case Input::near_plane: return v + "[19].z";
      case Input::far_plane: return v + "[19].w";
      case Input::convention: return "OBLIQUE_CONVENTION";
      case Input::view: return "oblique_matrix(i, 22)";
      case Input::inverse_view: return "oblique_matrix(i, 26)";
      case Input::view_projection: return "oblique_matrix(i, 30)";
      case Input::inverse_view_projection: return "oblique_matrix(i, 34)";
    }
    return "0";
  };
  std::string call = signature.name + "(";
  for (std::size_t k = 0; k < signature.parameters.size(); ++k)
    call += (k ? ", " : "") + argument(signature.parameters[k]);
  call += ")";
  const bool vector = glsl_type(signature.return_type) == "vec3";
  const std::string n = std::to_string(kRequestVectors);
  if (glsl) {
    out +=
        "layout(local_size_x = 64) in;\n"
        "struct ObliqueRequest { vec4 v[" +
        n +
        "]; };\n"
        "layout(std430, binding = 0) readonly buffer ObliqueRequests {\n"
        "  ObliqueRequest oblique_requests[];\n};\n"
        "layout(std430, binding = 1) writeonly buffer ObliqueAnswers {\n"
        "  vec4 oblique_answers[];\n};\n"
        "mat4 oblique_matrix(uint i, int at) {  // stored by rows\n"
        "  return " +
        std::string(row ? "(" : "transpose(") +
        "mat4(oblique_requests[i].v[at], oblique_requests[i].v[at + 1],\n"
        "                        oblique_requests[i].v[at + 2], oblique_requests[i].v[at + 3]));\n"
        "}\n"
        "void main() {\n"
        "  uint i = gl_GlobalInvocationID.x;\n";
    out += vector ? "  oblique_answers[i] = vec4(" + call + ", 0.0);\n"
                  : "  oblique_answers[i] = vec4(" + call + ", 0.0, 0.0, 0.0);\n";
    out += "}\n";
  } else {
    out += "struct ObliqueRequest { float4 v[" + n +
           "]; };\n"
           "[[vk::binding(0)]] StructuredBuffer<ObliqueRequest> oblique_requests;\n"
           "[[vk::binding(1)]] RWStructuredBuffer<float4> oblique_answers;\n"
           "float4x4 oblique_matrix(uint i, int at) {  // stored by rows\n"
           "  return " +
           std::string(row ? "transpose(" : "(") +
           "float4x4(oblique_requests[i].v[at], oblique_requests[i].v[at + 1],\n"
           "                  oblique_requests[i].v[at + 2], oblique_requests[i].v[at + 3]));\n"
           "}\n"
           "[numthreads(64, 1, 1)]\n"
           "void oblique_main(uint3 id : SV_DispatchThreadID) {\n"
           "  uint i = id.x;\n";
    out += vector ? "  oblique_answers[i] = float4(" + call + ", 0.0);\n"
                  : "  oblique_answers[i] = float4(" + call + ", 0.0, 0.0, 0.0);\n";
    out += "}\n";
  }
  return out;
}

}  // namespace oblique::shader
