// A headless OpenGL 4.5 core context (EGL's surfaceless platform, or Mesa's software device),
// the one every GPU tool of oblique draws or computes on: the rasterizer (raster.h) and the
// shader runner (oblique/shader/shader_runner.h).
#pragma once

#include <memory>
#include <string>

#include "oblique/depth_convention.h"
#include "oblique/expected.h"

namespace oblique::raster {

enum class Device {
  software,  ///< Mesa's llvmpipe (EGL_MESA_device_software): the same on every machine
  gpu,       ///< whatever the machine's EGL driver gives (its renderer is said)
};

/// While alive, Mesa writes no shader cache to $HOME (MESA_SHADER_CACHE_DISABLE, read when a
/// context is made and a shader built), unless the user set the variable; taken away again after.
/// The environment is the process's: a program a tool starts meanwhile inherits it.
class NoShaderCache {
 public:
  NoShaderCache();
  ~NoShaderCache();
  NoShaderCache(const NoShaderCache&) = delete;
  NoShaderCache& operator=(const NoShaderCache&) = delete;

 private:
  bool ours_;
};

class GlContext {
 public:
  /// Opens a context on `device`. Fails with one line beginning "no EGL" when there is nothing to
  /// render with (saying what to install), or saying which renderer was given instead of the one
  /// asked for (llvmpipe for software; a GPU's driver, not a software renderer, for gpu).
  static Expected<std::unique_ptr<GlContext>> open(Device device);
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  /// Makes the context current on the calling thread; false (with `error` set) when EGL refuses.
  bool make_current(std::string* error = nullptr);
  /// GL_RENDERER and GL_VERSION, as the driver says them.
  const std::string& renderer() const;
  Device device() const;

 private:
  struct State;
  explicit GlContext(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

/// On the current context: compiles the GLSL `vertex` and `fragment` shaders and links them into a
/// program (its name), or says which did not compile (with the compiler's log) or link.
Expected<unsigned> link_program(const char* vertex, const char* fragment);

/// On the current context: depth as an engine sets it for `convention`: glClipControl's [-1, 1]
/// for gl and [0, 1] for the others, no depth clamp, the depth test on with GL_LEQUAL (reversed Z:
/// GL_GEQUAL), the depth buffer cleared to the far value; returns that value (1; 0 reversed).
float set_engine_depth(Convention convention);

/// On the current context: "WHAT: GL error 0x0502" for the error GL has recorded since it was
/// last asked (clearing it), or "" when there is none.
std::string gl_error_after(const char* what);

}  // namespace oblique::raster
