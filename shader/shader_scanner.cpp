// The shader-source scanner (shader_scanner.h): one pass over the text, a fixed amount of work
// per byte; nothing recurses.
#include "oblique/shader/shader_scanner.h"

#include <algorithm>
#include <array>
#include <cctype>

namespace oblique::shader {

namespace {

bool word_start(char ch) {
  return std::isalpha(static_cast<unsigned char>(ch)) || ch == '_';
}
bool word_char(char ch) {
  return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_';
}
bool blank(char ch) {
  return ch == ' ' || ch == '\t' || ch == '\r' || ch == '\f' || ch == '\v';
}

bool one_of(std::string_view word, std::initializer_list<std::string_view> words) {
  return std::find(words.begin(), words.end(), word) != words.end();
}
bool starts_with(std::string_view word, std::string_view prefix) {
  return word.substr(0, prefix.size()) == prefix;
}

/// Why `word` reaches beyond a depth function's inputs; empty when it does not.
std::string_view reach(std::string_view w) {
  // Storage a shader writes or other invocations see: GLSL's storage blocks, images and atomic
  // counters; HLSL's read-write and structured buffers and textures (the runner's own buffers
  // are such).
  if (w == "buffer") return "declares a storage block, as the runner's own buffers are";
  if (w == "atomic_uint") return "declares an atomic counter";
  if (one_of(w, {"coherent", "volatile", "restrict", "readonly", "writeonly"}))
    return "qualifies the memory of a buffer or an image";
  for (const std::string_view prefix : {"image", "iimage", "uimage"}) {
    if (!starts_with(w, prefix) || w.size() == prefix.size()) continue;
    const std::string_view rest = w.substr(prefix.size());
    if (std::isdigit(static_cast<unsigned char>(rest[0])) != 0 ||
        one_of(rest, {"Cube", "CubeArray", "Buffer"}))
      return "declares an image";
  }
  if (starts_with(w, "RW") && w.size() > 2 && std::isupper(static_cast<unsigned char>(w[2])) != 0)
    return "declares a read-write resource";
  if (one_of(w, {"StructuredBuffer", "ByteAddressBuffer", "AppendStructuredBuffer",
                 "ConsumeStructuredBuffer", "RasterizerOrderedBuffer", "globallycoherent"}))
    return "declares a buffer";
  // Memory shared between the invocations of a work group.
  if (w == "shared" || w == "groupshared") return "declares memory shared between invocations";
  if (starts_with(w, "Interlocked") || starts_with(w, "atomic")) return "is an atomic operation";
  // Which invocation or lane it is, or another lane's values.
  if (one_of(w, {"gl_GlobalInvocationID", "gl_LocalInvocationID", "gl_LocalInvocationIndex",
                 "gl_WorkGroupID", "gl_NumWorkGroups", "gl_WorkGroupSize"}))
    return "tells the function which invocation it is";
  if (starts_with(w, "gl_Subgroup") || starts_with(w, "subgroup") || starts_with(w, "WaveActive") ||
      starts_with(w, "WavePrefix") || starts_with(w, "WaveMultiPrefix") ||
      starts_with(w, "WaveRead") || starts_with(w, "WaveGetLane") || w == "WaveIsFirstLane" ||
      w == "WaveMatch" || starts_with(w, "QuadRead") || starts_with(w, "gl_SM") ||
      starts_with(w, "gl_Warp") || starts_with(w, "ballotARB") ||
      starts_with(w, "readInvocationARB") || starts_with(w, "readFirstInvocationARB"))
    return "reads other lanes' values (a subgroup or wave operation)";
  if (one_of(w, {"barrier", "memoryBarrier", "memoryBarrierShared", "groupMemoryBarrier",
                 "GroupMemoryBarrierWithGroupSync", "GroupMemoryBarrier", "DeviceMemoryBarrier",
                 "AllMemoryBarrier"}))
    return "waits on other invocations";
  return {};
}

}  // namespace

std::string without_comments(std::string_view s) {
  std::string out(s);
  std::size_t i = 0;
  while (i + 1 < out.size()) {
    if (out[i] == '/' && out[i + 1] == '/') {
      for (; i < out.size() && out[i] != '\n'; ++i) out[i] = ' ';
    } else if (out[i] == '/' && out[i + 1] == '*') {
      const std::size_t end = out.find("*/", i + 2);
      const std::size_t stop = end == std::string::npos ? out.size() : end + 2;
      for (; i < stop; ++i)
        if (out[i] != '\n') out[i] = ' ';
    } else {
      ++i;
    }
  }
  return out;
}

std::vector<Token> tokens(std::string_view text) {
  std::vector<Token> out;
  int line = 1;
  bool line_start = true;  // only blanks so far on this line
  std::size_t i = 0;
  const std::size_t n = text.size();
  while (i < n) {
    const char ch = text[i];
    if (ch == '\n') {
      ++line;
      line_start = true;
      ++i;
      continue;
    }
    if (blank(ch)) {
      ++i;
      continue;
    }
    if (ch == '#' && line_start) {
      // A preprocessor line, continued by a backslash before its new line.
      for (; i < n && text[i] != '\n'; ++i) {
        if (text[i] == '\\' && i + 1 < n && text[i + 1] == '\n') {
          ++line;
          ++i;
        } else if (text[i] == '\\' && i + 2 < n && text[i + 1] == '\r' && text[i + 2] == '\n') {
          ++line;
          i += 2;
        }
      }
      continue;
    }
    line_start = false;
    const std::size_t start = i;
    Token t;
    t.line = line;
    if (word_start(ch)) {
      while (i < n && word_char(text[i])) ++i;
      t.kind = Token::Kind::identifier;
    } else if (std::isdigit(static_cast<unsigned char>(ch)) != 0 ||
               (ch == '.' && i + 1 < n && std::isdigit(static_cast<unsigned char>(text[i + 1])))) {
      while (i < n && (word_char(text[i]) || text[i] == '.')) ++i;
      t.kind = Token::Kind::number;
    } else {
      ++i;
      t.kind = Token::Kind::punctuation;
    }
    t.text = text.substr(start, i - start);
    out.push_back(t);
  }
  return out;
}

std::vector<Definition> definitions(const std::vector<Token>& t) {
  std::vector<Definition> out;
  const std::size_t n = t.size();
  auto is = [&](std::size_t k, Token::Kind kind) { return k < n && t[k].kind == kind; };
  auto punct = [&](std::size_t k, char ch) {
    return k < n && t[k].kind == Token::Kind::punctuation && t[k].text[0] == ch;
  };
  // Each '(' is looked at once, and the walk from it to the next parenthesis covers tokens no
  // other walk covers: linear in the tokens.
  for (std::size_t open = 2; open < n; ++open) {
    if (!punct(open, '(') || !is(open - 1, Token::Kind::identifier) ||
        !is(open - 2, Token::Kind::identifier))
      continue;
    const std::string_view name = t[open - 1].text;
    if (one_of(name, {"if", "for", "while", "switch", "return"})) continue;
    std::size_t close = open + 1;
    while (close < n && !punct(close, '(') && !punct(close, ')')) ++close;
    if (!punct(close, ')')) continue;
    std::size_t k = close + 1;
    if (punct(k, ':') && is(k + 1, Token::Kind::identifier)) k += 2;  // an HLSL semantic
    if (!punct(k, '{')) continue;
    Definition d;
    d.return_type = t[open - 2].text;
    d.name = name;
    d.line = t[open - 2].line;
    d.parameters.assign(t.begin() + static_cast<long>(open) + 1,
                        t.begin() + static_cast<long>(close));
    out.push_back(std::move(d));
    open = close;
  }
  return out;
}

std::optional<std::pair<std::size_t, std::size_t>> version_line(std::string_view text) {
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    std::size_t k = at;
    while (k < end && blank(text[k])) ++k;
    if (k < end && text[k] == '#') {
      ++k;
      while (k < end && blank(text[k])) ++k;
      constexpr std::string_view kVersion = "version";
      if (text.substr(k, kVersion.size()) == kVersion &&
          (k + kVersion.size() == end || !word_char(text[k + kVersion.size()])))
        return std::make_pair(at, end - at);
    }
    at = end + 1;
  }
  return std::nullopt;
}

std::optional<std::string> reaches_beyond_its_inputs(const std::vector<Token>& tokens) {
  for (const Token& t : tokens) {
    if (t.kind != Token::Kind::identifier) continue;
    const std::string_view why = reach(t.text);
    if (why.empty()) continue;
    std::string word(t.text.substr(0, 64));
    return "line " + std::to_string(t.line) + ": " + word + " " + std::string(why);
  }
  return std::nullopt;
}

}  // namespace oblique::shader
