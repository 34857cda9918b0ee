// libFuzzer target: the shader-source path without a compiler: the scanner (shader_scanner.h),
// the binding of a function's parameters by name (find_signature) and the generated wrapper
// (wrapped_source). The first byte chooses the language, the request kind, the function's name
// (view_position, linear_depth, or the first definition found) and the convention; the rest is
// the user's file. Checked, beyond "no crash, no hang": the tokens cover the text in order with
// their lines; every definition's name is an identifier token; a refusal has a message; a found
// function fits the kind and binds each parameter to an input of its type; the wrapper keeps the
// user's text line for line and calls the function with one argument per parameter; what reaches
// beyond a function's inputs names a word of the text.
#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "oblique/shader/shader_function.h"
#include "oblique/shader/shader_scanner.h"
#include "oblique/shader/shader_tools.h"

namespace {

using namespace oblique::shader;
using oblique::protocol::ConsumerKind;

[[noreturn]] void fail(const char* what, std::string_view detail) {
  std::fprintf(stderr, "shader source contract violated: %s\n%.*s\n", what,
               static_cast<int>(std::min<std::size_t>(detail.size(), 2000)), detail.data());
  std::abort();
}

bool identifier(std::string_view w) {
  if (w.empty() || !(std::isalpha(static_cast<unsigned char>(w[0])) || w[0] == '_')) return false;
  return std::all_of(w.begin(), w.end(), [](char ch) {
    return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_';
  });
}

std::size_t lines_in(std::string_view text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::uint8_t choice = data[0];
  const std::string source(reinterpret_cast<const char*>(data) + 1, size - 1);
  const Language language = (choice & 1) ? Language::hlsl : Language::glsl;
  const ConsumerKind kind = (choice & 2) ? ConsumerKind::linear_depth : ConsumerKind::view_position;
  const int convention = ((choice >> 2) & 3) % 3;

  // The scanner: comments blanked in place, tokens in order, definitions of identifiers.
  const std::string text = without_comments(source);
  if (text.size() != source.size() || lines_in(text) != lines_in(source))
    fail("comments removed changed the text's size or its lines", source);
  const std::vector<Token> tokens_found = tokens(text);
  const char* last = text.data();
  int last_line = 1;
  for (const Token& t : tokens_found) {
    if (t.text.empty() || t.text.data() < last ||
        t.text.data() + t.text.size() > text.data() + text.size())
      fail("a token out of order or outside the text", source);
    if (t.line < last_line ||
        static_cast<std::size_t>(t.line) !=
            1 + lines_in(std::string_view(text.data(),
                                          static_cast<std::size_t>(t.text.data() - text.data()))))
      fail("a token's line is not where it is", source);
    last = t.text.data() + t.text.size();
    last_line = t.line;
  }
  const std::vector<Definition> found = definitions(tokens_found);
  for (const Definition& d : found) {
    if (!identifier(d.name) || !identifier(d.return_type))
      fail("a definition named by no identifier", source);
  }
  if (const auto v = version_line(source)) {
    const std::string_view line = std::string_view(source).substr(v->first, v->second);
    if (line.find('\n') != std::string_view::npos || line.find('#') == std::string_view::npos)
      fail("a #version line that is none", source);
  }
  if (const auto beyond = reaches_beyond_its_inputs(tokens_found)) {
    if (beyond->rfind("line ", 0) != 0) fail("a reach without its line", *beyond);
  }

  // The binding: the function asked for (named after the kind, or the first definition).
  std::string function(kind == ConsumerKind::view_position ? "view_position" : "linear_depth");
  if ((choice & 16) && !found.empty()) function = std::string(found.front().name);
  const oblique::Expected<Signature> sig = find_signature(source, function, language, kind);
  if (!sig) {
    if (sig.error().empty()) fail("a refusal without a message", source);
    return 0;
  }
  if (sig->name != function) fail("the signature names another function", source);
  if (sig->line < 1 || static_cast<std::size_t>(sig->line) > lines_in(source) + 1)
    fail("the signature's line is outside the file", source);
  for (const Parameter& p : sig->parameters) {
    const auto& names = input_names(p.input);
    bool named = false;
    for (std::string_view n : names) {
      std::string a, b;
      for (char ch : n)
        if (ch != '_') a += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
      for (char ch : p.name)
        if (ch != '_') b += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
      named = named || a == b;
    }
    if (!named) fail("a parameter bound to an input its name is not", p.name);
  }

  // The wrapper: the user's lines where they were, one argument per parameter, the convention.
  const oblique::Expected<std::string> defines = define_lines({"ENGINE_DEFINE=1"});
  if (!defines) fail("a plain define refused", defines.error());
  const std::string wrapped = wrapped_source(source, "shader.glsl", *sig, language, convention,
                                             default_v_direction(language), *defines);
  if (wrapped.find("#define OBLIQUE_CONVENTION " + std::to_string(convention) + "\n") ==
      std::string::npos)
    fail("the wrapper does not define the convention", wrapped.substr(0, 400));
  if (wrapped.find("#define ENGINE_DEFINE 1\n") == std::string::npos)
    fail("the wrapper does not carry the engine's defines", wrapped.substr(0, 400));
  const std::size_t user_at = wrapped.find("#line 1");
  if (user_at == std::string::npos) fail("the wrapper has no #line for the user's text", source);
  const std::size_t user_from = wrapped.find('\n', user_at) + 1;
  if (language == Language::hlsl && wrapped.compare(user_from, source.size(), source) != 0)
    fail("the wrapper changed the user's HLSL", source);
  if (lines_in(std::string_view(wrapped).substr(user_from, source.size())) != lines_in(source) &&
      language == Language::glsl && !version_line(source))
    fail("the wrapper moved the user's lines", source);
  const std::string call = sig->name + "(";
  const std::size_t call_at = wrapped.rfind(call);
  if (call_at == std::string::npos || call_at < user_from + source.size() - 1)
    fail("the wrapper does not call the function", source);
  // Each argument is one of the wrapper's reads: a matrix, a request's vector or the convention.
  const std::size_t line_end = std::min(wrapped.find('\n', call_at), wrapped.size());
  const std::string_view arguments(wrapped.data() + call_at + call.size(),
                                   line_end - call_at - call.size());
  std::size_t reads = 0;
  for (const std::string_view read : {"oblique_matrix(", "oblique_requests[", "OBLIQUE_CONVENTION"})
    for (std::size_t at = arguments.find(read); at != std::string_view::npos;
         at = arguments.find(read, at + 1))
      ++reads;
  if (reads != sig->parameters.size())
    fail("the wrapper's call has not one argument per parameter", source);
  return 0;
}
