// Text between us and other programs: their bytes made printable, words quoted for /bin/sh, a
// command named as tables show it.
#pragma once

#include <streambuf>
#include <string>
#include <string_view>

namespace oblique::protocol {

/// Bytes from another program as printable text: valid UTF-8 (newlines and tabs included) kept,
/// every other byte (invalid or cut UTF-8, control characters) as \xNN.
std::string escape_bytes(std::string_view bytes);

/// A stream buffer that passes what is written to `to` a line at a time through escape_bytes():
/// set on std::cerr, every message that echoes a path, a name or a program's output reaches the
/// terminal with its control characters (ESC [2J, a window title) shown, not obeyed.
class EscapingBuffer : public std::streambuf {
 public:
  explicit EscapingBuffer(std::streambuf* to);
  ~EscapingBuffer() override;
  EscapingBuffer(const EscapingBuffer&) = delete;
  EscapingBuffer& operator=(const EscapingBuffer&) = delete;

 protected:
  int_type overflow(int_type ch) override;
  std::streamsize xsputn(const char* s, std::streamsize n) override;
  int sync() override;

 private:
  void pass_line();
  std::streambuf* to_;
  std::string line_;
};

/// `s` quoted for /bin/sh when it needs it (a word of letters, digits and _./=,:+-@% as it is).
std::string shell_quote(const std::string& s);

/// A command as tables and charts name it: each word that names a file without its folder
/// ("python3 /x/y/impl.py --float" is "python3 impl.py --float"), at most 60 characters.
std::string command_name(const std::string& command);

}  // namespace oblique::protocol
