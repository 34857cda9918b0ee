#include "oblique/protocol/shell_text.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>

namespace oblique::protocol {

namespace {

std::size_t utf8_sequence_length(std::string_view s, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char b = byte(i);
  std::size_t n = 0;
  if (b >= 0xC2 && b <= 0xDF) {
    n = 2;
  } else if (b >= 0xE0 && b <= 0xEF) {
    n = 3;
  } else if (b >= 0xF0 && b <= 0xF4) {
    n = 4;
  } else {
    return 0;
  }
  if (i + n > s.size()) return 0;  // cut short
  for (std::size_t k = 1; k < n; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
  }
  // Overlong forms, surrogates and code points beyond U+10FFFF.
  if (b == 0xE0 && byte(i + 1) < 0xA0) return 0;
  if (b == 0xED && byte(i + 1) >= 0xA0) return 0;
  if (b == 0xF0 && byte(i + 1) < 0x90) return 0;
  if (b == 0xF4 && byte(i + 1) >= 0x90) return 0;
  // The C1 controls (U+0080 to U+009F): some terminals take U+009B as ESC [.
  if (b == 0xC2 && byte(i + 1) < 0xA0) return 0;
  return n;
}

}  // namespace

std::string shell_quote(const std::string& s) {
  const bool plain = !s.empty() && std::all_of(s.begin(), s.end(), [](char ch) {
    return std::isalnum(static_cast<unsigned char>(ch)) || std::strchr("_./=,:+-@%", ch);
  });
  if (plain) return s;
  std::string out = "'";
  for (char ch : s) out += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return out + "'";
}

std::string command_name(const std::string& command) {
  std::string out, word;
  auto flush = [&] {
    if (word.empty()) return;
    const std::size_t slash = word.rfind('/');
    if (slash != std::string::npos && slash + 1 < word.size()) word = word.substr(slash + 1);
    out += (out.empty() ? "" : " ") + word;
    word.clear();
  };
  for (char ch : command) {
    if (std::isspace(static_cast<unsigned char>(ch)))
      flush();
    else
      word += ch;
  }
  flush();
  return out.size() > 60 ? out.substr(0, 57) + "..." : out;
}

std::string escape_bytes(std::string_view bytes) {
  std::string out;
  out.reserve(bytes.size());
  for (std::size_t i = 0; i < bytes.size();) {
    const auto b = static_cast<unsigned char>(bytes[i]);
    if ((b >= 0x20 && b < 0x7F) || b == '\n' || b == '\t') {
      out += static_cast<char>(b);
      ++i;
    } else if (const std::size_t n = b >= 0x80 ? utf8_sequence_length(bytes, i) : 0) {
      out.append(bytes.substr(i, n));
      i += n;
    } else {
      char hex[5];
      std::snprintf(hex, sizeof hex, "\\x%02X", b);
      out += hex;
      ++i;
    }
  }
  return out;
}

EscapingBuffer::EscapingBuffer(std::streambuf* to) : to_(to) {}

EscapingBuffer::~EscapingBuffer() {
  pass_line();
  if (to_) to_->pubsync();
}

void EscapingBuffer::pass_line() {
  if (line_.empty() || !to_) return;
  const std::string out = escape_bytes(line_);
  to_->sputn(out.data(), static_cast<std::streamsize>(out.size()));
  line_.clear();
}

EscapingBuffer::int_type EscapingBuffer::overflow(int_type ch) {
  if (traits_type::eq_int_type(ch, traits_type::eof())) return traits_type::not_eof(ch);
  line_ += traits_type::to_char_type(ch);
  if (line_.back() == '\n' || line_.size() >= 4096) pass_line();
  return ch;
}

std::streamsize EscapingBuffer::xsputn(const char* s, std::streamsize n) {
  for (std::streamsize k = 0; k < n; ++k) overflow(traits_type::to_int_type(s[k]));
  return n;
}

int EscapingBuffer::sync() {
  pass_line();
  return to_ ? to_->pubsync() : 0;
}

}  // namespace oblique::protocol
