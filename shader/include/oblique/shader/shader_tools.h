// The shader tools run as programs of their own (glslangValidator to preprocess and check, and
// to turn HLSL into SPIR-V; spirv-cross back to GLSL), each under a time limit (the caller's
// --timeout) and an address-space limit (kToolAddressSpaceBytes), in a process group the
// interrupt handler ends: a macro bomb, a file that takes minutes or an `#if` that spins the
// preprocessor is stopped and said, never waited for.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "oblique/expected.h"
#include "oblique/shader/shader_function.h"

namespace oblique::shader {

/// The memory a tool may map (ulimit -v): glslang needs tens of MiB for a real shader.
inline constexpr std::size_t kToolAddressSpaceBytes = std::size_t{1} << 30;
/// The least time a tool is given, whatever the caller's limit: a request's --timeout may be a
/// millisecond, and no tool starts that fast.
inline constexpr double kToolLeastSeconds = 1;
/// The most a tool's output may hold (a preprocessed file; a file is at most kMaxShaderBytes).
inline constexpr std::size_t kToolOutputBytes = std::size_t{64} << 20;

/// `#define` lines for `defines` (NAME or NAME=VALUE, as -D takes them; NAME alone is 1). The
/// error names a define that is not an identifier or holds a new line.
Expected<std::string> define_lines(const std::vector<std::string>& defines);

/// The user's `source` as the preprocessor keeps it under `defines` (the `#define` lines) for
/// `language`: comments gone, `#if` branches chosen, macros expanded, each line where it was.
/// Run by glslangValidator -E within `seconds`; the error says what stopped it, the user's file
/// (`path`) and line named.
Expected<std::string> preprocessed(const std::string& source, const std::string& path,
                                   Language language, const std::string& defines, double seconds);

/// Whether glslang compiles the GLSL compute shader `glsl` within `seconds`: said before the
/// driver is given it, so a file the driver would take minutes or gigabytes on is stopped here.
/// The error is glslang's log, lines mapped to the user's file `path`.
Expected<Done> glsl_compiles(const std::string& glsl, const std::string& path, double seconds);

/// The HLSL wrapped source as GLSL 4.50: glslangValidator to SPIR-V, spirv-cross back to GLSL,
/// each within `seconds`.
Expected<std::string> hlsl_as_glsl(const std::string& hlsl, double seconds);

}  // namespace oblique::shader
