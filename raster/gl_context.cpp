// The headless OpenGL 4.5 context (gl_context.h): EGL's surfaceless platform through glvnd, or
// Mesa's software device, chosen without touching the environment.
#define GL_GLEXT_PROTOTYPES 1
#define EGL_EGLEXT_PROTOTYPES 1
#include "oblique/raster/gl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <mutex>
#include <string>

namespace oblique::raster {

namespace {

constexpr const char* kPackages = "libegl-mesa0 libgl1-mesa-dri (and libegl1, libopengl0)";

/// What to do when EGL finds no Mesa: install the packages, unless Mesa's EGL is there and only
/// glvnd's vendor file that points at it is missing (or the environment points glvnd elsewhere).
std::string install_hint() {
  for (const char* variable : {"__EGL_VENDOR_LIBRARY_FILENAMES", "__EGL_VENDOR_LIBRARY_DIRS"}) {
    if (const char* v = std::getenv(variable))
      return std::string(variable) + " is set (" + v +
             "): glvnd looks for EGL vendors only there; unset it or point it at Mesa's "
             "50_mesa.json";
  }
  namespace fs = std::filesystem;
  std::error_code ec;
  bool library = false;
  for (const char* dir :
       {"/usr/lib/x86_64-linux-gnu", "/usr/lib/aarch64-linux-gnu", "/usr/lib64", "/usr/lib"})
    library = library || fs::exists(fs::path(dir) / "libEGL_mesa.so.0", ec);
  bool vendor = false;
  for (const char* dir : {"/usr/share/glvnd/egl_vendor.d", "/etc/glvnd/egl_vendor.d"})
    vendor = vendor || fs::exists(fs::path(dir) / "50_mesa.json", ec);
  if (library && !vendor)
    return "Mesa's EGL (libEGL_mesa.so.0) is installed, but glvnd's vendor file for it "
           "(/usr/share/glvnd/egl_vendor.d/50_mesa.json) is missing: reinstall libegl-mesa0 "
           "(apt-get install --reinstall libegl-mesa0)";
  return std::string("install ") + kPackages;
}

std::string egl_error(const char* what) {
  char line[96];
  std::snprintf(line, sizeof line, "%s failed (EGL error 0x%04x)", what,
                static_cast<unsigned>(eglGetError()));
  return line;
}

/// EGL gives one display per platform and device, shared by every Rasterizer of the process, and
/// eglTerminate() ends every context on it: the last Rasterizer to use a display terminates it.
std::mutex display_mutex;
std::map<EGLDisplay, int> display_users;

void use_display(EGLDisplay display) {
  const std::lock_guard<std::mutex> lock(display_mutex);
  ++display_users[display];
}

void release_display(EGLDisplay display) {
  const std::lock_guard<std::mutex> lock(display_mutex);
  if (--display_users[display] > 0) return;
  display_users.erase(display);
  eglTerminate(display);
}

}  // namespace

struct GlContext::State {
  Device device = Device::software;
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  std::string renderer;
  bool display_used = false;  ///< initialized and counted (use_display())

  ~State() {
    if (context != EGL_NO_CONTEXT) {
      eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      eglDestroyContext(display, context);
    }
    if (display_used) release_display(display);
  }

  /// Mesa's software device (EGL_MESA_device_software): llvmpipe whatever the machine has,
  /// chosen without touching the environment (which verify's implementation inherits).
  EGLDisplay software_display() {
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!client || !std::strstr(client, "EGL_EXT_device_enumeration") ||
        !std::strstr(client, "EGL_EXT_platform_device"))
      return EGL_NO_DISPLAY;
    const auto query_devices =
        reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    const auto device_string = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(
        eglGetProcAddress("eglQueryDeviceStringEXT"));
    if (!query_devices || !device_string) return EGL_NO_DISPLAY;
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (!query_devices(16, devices, &count)) return EGL_NO_DISPLAY;
    for (EGLint i = 0; i < count; ++i) {
      const char* extensions = device_string(devices[i], EGL_EXTENSIONS);
      if (extensions && std::strstr(extensions, "EGL_MESA_device_software"))
        return eglGetPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
    }
    return EGL_NO_DISPLAY;
  }

  Expected<Done> start() {
    const NoShaderCache no_cache;
    return open_context();
  }

  Expected<Done> open_context() {
    if (device == Device::software) {
      display = software_display();
      if (display == EGL_NO_DISPLAY)
        return Expected<Done>::failure(
            std::string("no EGL software device (EGL_MESA_device_software): ") + install_hint());
    } else {
      const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
      if (!client || !std::strstr(client, "EGL_MESA_platform_surfaceless"))
        return Expected<Done>::failure(std::string("no EGL with the surfaceless platform: ") +
                                       install_hint());
      display = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    }
    EGLint major = 0, minor = 0;
    if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor))
      return Expected<Done>::failure("no EGL device (" + egl_error("eglInitialize") +
                                     "): " + install_hint());
    use_display(display);
    display_used = true;
    if (!eglBindAPI(EGL_OPENGL_API)) return Expected<Done>::failure(egl_error("eglBindAPI"));
    const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                 4,
                                 EGL_CONTEXT_MINOR_VERSION,
                                 5,
                                 EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                 EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                 EGL_NONE};
    context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
    if (context == EGL_NO_CONTEXT)
      return Expected<Done>::failure(egl_error("an OpenGL 4.5 core context"));
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context))
      return Expected<Done>::failure(egl_error("eglMakeCurrent"));
    const auto* name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    renderer = std::string(name ? name : "?") + ", OpenGL " + (version ? version : "?");
    if (device == Device::software && renderer.find("llvmpipe") == std::string::npos)
      return Expected<Done>::failure("asked for llvmpipe, the driver gave " + renderer);
    // A user who asked for a GPU is told when there is none, not given llvmpipe in silence.
    if (device == Device::gpu && (renderer.find("llvmpipe") != std::string::npos ||
                                  renderer.find("softpipe") != std::string::npos))
      return Expected<Done>::failure(
          "asked for a GPU (--device gpu), but EGL gave the software "
          "renderer " +
          renderer +
          ": no GPU is reachable here (--device software draws on "
          "llvmpipe)");
    return Done{};
  }
};

NoShaderCache::NoShaderCache() : ours_(std::getenv("MESA_SHADER_CACHE_DISABLE") == nullptr) {
  if (ours_) setenv("MESA_SHADER_CACHE_DISABLE", "true", 0);
}

NoShaderCache::~NoShaderCache() {
  if (ours_) unsetenv("MESA_SHADER_CACHE_DISABLE");
}

GlContext::GlContext(std::unique_ptr<State> state) : state_(std::move(state)) {}
GlContext::~GlContext() = default;

Expected<unsigned> link_program(const char* vertex, const char* fragment) {
  const GLuint shaders[2] = {glCreateShader(GL_VERTEX_SHADER), glCreateShader(GL_FRAGMENT_SHADER)};
  const char* sources[2] = {vertex, fragment};
  const GLuint program = glCreateProgram();
  std::string failed;
  for (int s = 0; s < 2 && failed.empty(); ++s) {
    glShaderSource(shaders[s], 1, &sources[s], nullptr);
    glCompileShader(shaders[s]);
    GLint ok = 0;
    glGetShaderiv(shaders[s], GL_COMPILE_STATUS, &ok);
    if (!ok) {
      char log[512] = {};
      glGetShaderInfoLog(shaders[s], sizeof log, nullptr, log);
      failed =
          std::string(s == 0 ? "the vertex" : "the fragment") + " shader did not compile: " + log;
    }
    glAttachShader(program, shaders[s]);
  }
  if (failed.empty()) glLinkProgram(program);
  glDeleteShader(shaders[0]);
  glDeleteShader(shaders[1]);
  GLint linked = 0;
  if (failed.empty()) glGetProgramiv(program, GL_LINK_STATUS, &linked);
  if (failed.empty() && !linked) failed = "the shaders did not link";
  if (!failed.empty()) {
    glDeleteProgram(program);
    return Expected<unsigned>::failure(failed);
  }
  return program;
}

float set_engine_depth(Convention convention) {
  glClipControl(GL_LOWER_LEFT,
                convention == Convention::gl ? GL_NEGATIVE_ONE_TO_ONE : GL_ZERO_TO_ONE);
  glDisable(GL_DEPTH_CLAMP);
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  // Reversed Z as engines set it: cleared to 0, GL_GEQUAL; the others cleared to 1, GL_LEQUAL.
  const bool reversed = convention == Convention::reversed_z;
  glDepthFunc(reversed ? GL_GEQUAL : GL_LEQUAL);
  const GLfloat far_value = reversed ? 0.0f : 1.0f;
  glClearBufferfv(GL_DEPTH, 0, &far_value);
  return far_value;
}

std::string gl_error_after(const char* what) {
  const GLenum e = glGetError();
  if (e == GL_NO_ERROR) return "";
  char line[160];
  std::snprintf(line, sizeof line, "%s: GL error 0x%04x", what, static_cast<unsigned>(e));
  return line;
}

Expected<std::unique_ptr<GlContext>> GlContext::open(Device device) {
  auto state = std::make_unique<State>();
  state->device = device;
  if (const Expected<Done> started = state->start(); !started)
    return Expected<std::unique_ptr<GlContext>>::failure(started.error());
  return std::unique_ptr<GlContext>(new GlContext(std::move(state)));
}

bool GlContext::make_current(std::string* error) {
  if (eglMakeCurrent(state_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, state_->context)) return true;
  if (error) *error = egl_error("eglMakeCurrent");
  return false;
}

const std::string& GlContext::renderer() const {
  return state_->renderer;
}

Device GlContext::device() const {
  return state_->device;
}

}  // namespace oblique::raster
