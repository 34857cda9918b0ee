// The shader-source scanner: a user's file read as tokens in one pass, without regular
// expressions or recursion that grows with the input, so a file of one 16 MiB identifier, of
// comments or of parameters is read in time linear in its size (issue 64: std::regex recursed once
// per character and overflowed the stack). It finds function definitions, the #version line and
// what a depth function must not declare (the runner's buffers, memory shared between
// invocations, which invocation it is).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace oblique::shader {

/// The source with comments replaced by spaces (new lines kept, so lines still count). A comment
/// left open runs to the end.
std::string without_comments(std::string_view source);

struct Token {
  enum class Kind { identifier, number, punctuation };
  Kind kind = Kind::punctuation;
  std::string_view text;  ///< a view of the scanned text
  int line = 1;           ///< from 1
};

/// The tokens of `text` (comments already removed): identifiers, numbers and single punctuation
/// characters. Preprocessor lines (a '#' first on its line, continued by a final backslash) are
/// left out: their words are the preprocessor's, not the language's.
std::vector<Token> tokens(std::string_view text);

/// A function definition: `return_type name(parameters) [: semantic] {`, its parameters as the
/// tokens between the parentheses (no parenthesis among them).
struct Definition {
  std::string_view return_type, name;
  std::vector<Token> parameters;
  int line = 1;
};

/// Every function definition among `tokens` (if, for, while, switch and return are no names).
std::vector<Definition> definitions(const std::vector<Token>& tokens);

/// Where the GLSL `#version` line is in `text`: its first byte and its length (no new line), or
/// none. Only a line whose first word is the directive counts.
std::optional<std::pair<std::size_t, std::size_t>> version_line(std::string_view text);

/// The first word among `tokens` that reaches beyond a depth function's own inputs (a buffer,
/// an image or an atomic counter another invocation reads or the runner writes; memory shared
/// between invocations; which invocation or lane it is), and why, as "line N: buffer declares a
/// storage block, ..."; none when there is none.
std::optional<std::string> reaches_beyond_its_inputs(const std::vector<Token>& tokens);

}  // namespace oblique::shader
