// The shader tools under limits (shader_tools.h): each a child process in a group of its own
// (protocol::ChildProcess: the interrupt handler ends it), started by /bin/sh under `ulimit -v`,
// stopped at its deadline.
#include "oblique/shader/shader_tools.h"

#include <stdlib.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>

#include "oblique/protocol/child_process.h"
#include "oblique/protocol/interrupts.h"
#include "oblique/protocol/shell_text.h"
#include "oblique/shader/shader_scanner.h"

namespace oblique::shader {

namespace {

constexpr const char* kToolPackages = "glslang-tools spirv-cross";

/// A temporary folder, removed with everything in it when this goes.
struct TempFolder {
  std::filesystem::path path;
  TempFolder() {
    std::error_code ec;
    const std::filesystem::path base = std::filesystem::temp_directory_path(ec);
    if (ec) return;  // path stays empty: the caller says it cannot make one
    std::string pattern = (base / "oblique-shader-XXXXXX").string();
    if (!mkdtemp(pattern.data())) return;
    path = pattern;
    protocol::remove_on_interrupt(path.string(), true);  // an interrupt leaves no folder behind
  }
  ~TempFolder() {
    std::error_code ec;
    if (path.empty()) return;
    std::filesystem::remove_all(path, ec);
    protocol::keep_on_interrupt(path.string());
  }
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;
};

/// Whether `name` is on PATH, looked for once per process (a shader's open runs the tools six
/// times and more).
bool tool_present(const std::string& name) {
  static std::mutex looking;
  static std::map<std::string, bool> found;
  const std::lock_guard<std::mutex> lock(looking);
  if (const auto it = found.find(name); it != found.end()) return it->second;
  protocol::ChildProcess which("command -v " + name + " > /dev/null");
  bool present = false;
  if (which.start()) {
    std::string out;
    int status = 1;
    which.run_to_end(out, 0, protocol::Clock::now() + std::chrono::seconds(10), status);
    present = status == 0;
  }
  return found[name] = present;
}

std::string gib(std::size_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%g GiB", static_cast<double>(bytes) / (1u << 30));
  return text;
}

struct ToolRun {
  bool ok = false;
  std::string output;  ///< its standard output and error
  std::string error;   ///< why it did not succeed: empty when it only failed (see output)
};

/// Runs `command` (a tool and its arguments, quoted) with its output joined, under the limits.
ToolRun run_limited(const std::string& tool, const std::string& arguments, double seconds,
                    const std::string& what) {
  ToolRun run;
  seconds = std::max(seconds, kToolLeastSeconds);
  const std::string command = "ulimit -v " + std::to_string(kToolAddressSpaceBytes >> 10) +
                              " && exec " + tool + " " + arguments + " 2>&1";
  // An interrupt ends the tool's process group (ChildProcess) and says what it stopped.
  protocol::set_interrupt_line("oblique: interrupted while " + what + " (" + tool +
                               "); nothing was judged");
  struct ClearLine {
    ~ClearLine() { protocol::set_interrupt_line(""); }
  } clear_line;
  protocol::ChildProcess child(command);
  if (const Expected<Done> started = child.start(); !started) {
    run.error = "cannot start " + tool + ": " + started.error();
    return run;
  }
  int status = 0;
  const auto deadline =
      protocol::Clock::now() +
      std::chrono::duration_cast<protocol::Clock::duration>(std::chrono::duration<double>(seconds));
  const protocol::ChildProcess::Outcome outcome =
      child.run_to_end(run.output, kToolOutputBytes + 1, deadline, status);
  char limit[64];
  std::snprintf(limit, sizeof limit, "%g s", seconds);
  if (outcome == protocol::ChildProcess::Outcome::timed_out) {
    run.error = what + " did not finish within " + limit +
                " (--timeout; stopped: a macro that expands without end, or a file too large?)";
    return run;
  }
  if (run.output.size() > kToolOutputBytes) {
    run.error = what + " wrote more than " + std::to_string(kToolOutputBytes >> 20) +
                " MiB (stopped: a macro that expands without end?)";
    return run;
  }
  if (status > 128) {
    run.error = what + " stopped (" + tool + " " + child.end_description() + ") within the " +
                gib(kToolAddressSpaceBytes) +
                " of memory a tool is given (a macro that expands without end?)";
    return run;
  }
  run.ok = status == 0;
  return run;
}

/// glslang's messages ("ERROR: 0:12: ..." or "ERROR: FILE:12: ...") with their lines named: the
/// user's file's, or the wrapper's from kWrapperFirstLine. Lines naming only the input file and
/// glslang's summary lines are left out.
std::string mapped_glslang_log(const std::string& log, const std::string& input,
                               const std::string& path) {
  std::string out;
  std::istringstream lines(log);
  for (std::string line; std::getline(lines, line);) {
    if (line == input || line.empty() || line.rfind("SPIR-V is not generated", 0) == 0 ||
        line.find("compilation errors.  No code generated") != std::string::npos)
      continue;
    for (const std::string prefix : {"ERROR: ", "WARNING: "}) {
      if (line.rfind(prefix, 0) != 0) continue;
      const std::size_t at = prefix.size();
      std::size_t colon = line.find(':', at);
      const std::string source = colon == std::string::npos ? "" : line.substr(at, colon - at);
      if (source != "0" && source != input) break;
      std::size_t k = colon + 1;
      long number = 0;
      while (k < line.size() && std::isdigit(static_cast<unsigned char>(line[k])) && k < colon + 10)
        number = number * 10 + (line[k++] - '0');
      if (k == colon + 1 || k >= line.size() || line[k] != ':') break;
      const std::string where =
          number < kWrapperFirstLine
              ? path + ":" + std::to_string(number)
              : "(oblique's wrapper, line " + std::to_string(number - kWrapperFirstLine + 1) + ")";
      line = prefix + where + line.substr(k);
      break;
    }
    if (line.size() > 400) line = line.substr(0, 400) + "...";
    out += "  " + line + "\n";
  }
  return out;
}

Expected<Done> need(const char* tool, const std::string& what) {
  if (tool_present(tool)) return Done{};
  return Expected<Done>::failure(what + " needs " + tool + ", which is not installed: install " +
                                 kToolPackages + " (bash scripts/setup.sh)");
}

}  // namespace

Expected<std::string> define_lines(const std::vector<std::string>& defines) {
  std::string out;
  for (const std::string& d : defines) {
    const std::size_t eq = d.find('=');
    const std::string name = d.substr(0, eq);
    const std::string value = eq == std::string::npos ? "1" : d.substr(eq + 1);
    const bool identifier = !name.empty() && !std::isdigit(static_cast<unsigned char>(name[0])) &&
                            name.find_first_not_of(
                                "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRS"
                                "TUVWXYZ0123456789_") == std::string::npos;
    if (!identifier)
      return Expected<std::string>::failure("the define " + protocol::escape_bytes(d) +
                                            " does not start with a name (NAME or NAME=VALUE)");
    if (value.find_first_of("\r\n") != std::string::npos ||
        (!value.empty() && value.back() == '\\'))
      return Expected<std::string>::failure("the define " + name +
                                            " has a value of more than one line");
    if (value.find("/*") != std::string::npos)
      return Expected<std::string>::failure(
          "the define " + name +
          " has a value that opens a comment (/*): it would run on into "
          "the shader");
    out += "#define " + name + " " + value + "\n";
  }
  return out;
}

Expected<std::string> preprocessed(const std::string& source, const std::string& path,
                                   Language language, const std::string& defines, double seconds) {
  using Text = Expected<std::string>;
  const bool glsl = language == Language::glsl;
  if (const Expected<Done> has = need("glslangValidator", glsl ? "GLSL" : "HLSL"); !has)
    return Text::failure(has.error());
  const TempFolder folder;
  if (folder.path.empty())
    return Text::failure(
        "cannot make a temporary folder for glslang's files (is TMPDIR a writable folder?)");
  const std::string in = (folder.path / (glsl ? "source.comp" : "source.hlsl")).string();
  // The user's #version is ours to give; the rest is theirs, line for line after "#line 1".
  std::string user = source;
  if (glsl) {
    if (const auto v = version_line(user)) user.replace(v->first, v->second, "");
  }
  std::string text = glsl ? "#version 450 core\n" : "";
  text += defines + "#line 1\n" + user + "\n";
  std::ofstream(in, std::ios::binary) << text;
  const ToolRun run = run_limited("glslangValidator",
                                  std::string("-E ") + (glsl ? "" : "-D -e oblique_main ") +
                                      "-S comp " + protocol::shell_quote(in),
                                  seconds, "preprocessing " + path);
  if (!run.error.empty()) return Text::failure(run.error);
  if (!run.ok)
    return Text::failure("the shader did not preprocess (glslang):\n" +
                         mapped_glslang_log(run.output, in, path));
  // The user's part: after the first line "#line 1" (the define lines before it are blank now).
  std::size_t mark = run.output.rfind("#line 1\n", 0) == 0 ? 0 : run.output.find("\n#line 1\n");
  if (mark == std::string::npos)
    return Text::failure(
        "glslang's preprocessed output lost its #line mark (glslang changed "
        "its output?)");
  if (mark != 0) ++mark;
  return run.output.substr(mark + 8);
}

Expected<Done> glsl_compiles(const std::string& glsl, const std::string& path, double seconds) {
  if (const Expected<Done> has = need("glslangValidator", "GLSL"); !has) return has;
  const TempFolder folder;
  if (folder.path.empty())
    return Expected<Done>::failure(
        "cannot make a temporary folder for glslang's files (is TMPDIR a writable folder?)");
  const std::string in = (folder.path / "wrapped.comp").string();
  std::ofstream(in, std::ios::binary) << glsl;
  const ToolRun run = run_limited("glslangValidator", "-S comp " + protocol::shell_quote(in),
                                  seconds, "compiling " + path);
  if (!run.error.empty()) return Expected<Done>::failure(run.error);
  if (!run.ok)
    return Expected<Done>::failure("the shader did not compile (glslang):\n" +
                                   mapped_glslang_log(run.output, in, path));
  return Done{};
}

Expected<std::string> hlsl_as_glsl(const std::string& hlsl, double seconds) {
  using Text = Expected<std::string>;
  for (const char* tool : {"glslangValidator", "spirv-cross"}) {
    if (const Expected<Done> has = need(tool, "HLSL"); !has) return Text::failure(has.error());
  }
  const TempFolder folder;
  if (folder.path.empty())
    return Text::failure(
        "cannot make a temporary folder for glslang's files (is TMPDIR a writable folder?)");
  const std::string in = (folder.path / "wrapped.hlsl").string();
  const std::string spv = (folder.path / "wrapped.spv").string();
  const std::string glsl = (folder.path / "wrapped.comp").string();
  std::ofstream(in, std::ios::binary) << hlsl;
  const ToolRun compiled =
      run_limited("glslangValidator",
                  "-D -V -S comp -e oblique_main -o " + protocol::shell_quote(spv) + " " +
                      protocol::shell_quote(in),
                  seconds, "compiling the HLSL");
  if (!compiled.error.empty()) return Text::failure(compiled.error);
  // glslang's messages name the user's file and line already (the wrapper's #line).
  if (!compiled.ok)
    return Text::failure("the HLSL did not compile (glslang):\n" +
                         mapped_glslang_log(compiled.output, in, in));
  const ToolRun crossed = run_limited("spirv-cross",
                                      "--version 450 --no-es " + protocol::shell_quote(spv) +
                                          " --output " + protocol::shell_quote(glsl),
                                      seconds, "spirv-cross");
  if (!crossed.error.empty()) return Text::failure(crossed.error);
  if (!crossed.ok)
    return Text::failure("spirv-cross could not turn the SPIR-V into GLSL: " +
                         protocol::escape_bytes(crossed.output));
  return read_shader_file(glsl);
}

}  // namespace oblique::shader
