// The shader runner (shader_runner.h): the user's functions wrapped, compiled (HLSL through
// glslang and spirv-cross) and run as compute shaders on the headless GL context.
#define GL_GLEXT_PROTOTYPES 1
#include "oblique/shader/shader_runner.h"

#include <GL/glcorearb.h>
#include <unistd.h>

#include <cctype>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "oblique/depth_convention.h"
#include "oblique/oracle/consumer_wire.h"
#include "oblique/protocol/interrupts.h"
#include "oblique/protocol/shell_text.h"
#include "oblique/references/depth_reconstruction.h"
#include "oblique/shader/shader_scanner.h"
#include "oblique/shader/shader_tools.h"

namespace oblique::shader {

namespace {

using protocol::ConsumerKind;

constexpr int kKinds = 3;  // view_position, linear_depth, world_position
constexpr GLuint kGroupSize = 64;
constexpr ConsumerKind kShaderKinds[kKinds] = {
    ConsumerKind::view_position, ConsumerKind::linear_depth, ConsumerKind::world_position};

int kind_index(ConsumerKind kind) {
  for (int k = 0; k < kKinds; ++k)
    if (kShaderKinds[k] == kind) return k;
  return -1;
}

constexpr const char* kShaderKindsText = "view_position, linear_depth and world_position";

/// A GL compiler's log with its lines named: the user's file's, or the wrapper's from
/// kWrapperFirstLine (Mesa writes "0:12(5): error: ...", others "0(12) : error ...").
std::string mapped_log(const std::string& log, const std::string& path) {
  auto where = [&path](long n) {
    if (n < kWrapperFirstLine) return path + ":" + std::to_string(n);
    return "(oblique's wrapper, line " + std::to_string(n - kWrapperFirstLine + 1) + ")";
  };
  // Digits from `k`: their value (at most 9 of them) and where they end.
  auto number = [](const std::string& s, std::size_t k, long& value) {
    const std::size_t from = k;
    value = 0;
    while (k < s.size() && k < from + 9 && std::isdigit(static_cast<unsigned char>(s[k])))
      value = value * 10 + (s[k++] - '0');
    return k == from ? std::string::npos : k;
  };
  std::string out;
  std::istringstream lines(log);
  for (std::string line; std::getline(lines, line);) {
    long source = 0, n = 0, column = 0;
    std::size_t k = number(line, 0, source);
    if (k != std::string::npos && k < line.size() && line[k] == ':') {
      // Mesa: "0:12(5): error: ..."
      const std::size_t c = number(line, k + 1, n);
      std::size_t e = c == std::string::npos || c >= line.size() || line[c] != '('
                          ? std::string::npos
                          : number(line, c + 1, column);
      if (e != std::string::npos && line.compare(e, 3, "): ") == 0)
        line = where(n) + ":" + std::to_string(column) + ": " + line.substr(e + 3);
    } else if (k != std::string::npos && k < line.size() && line[k] == '(') {
      // Others: "0(12) : error ..."
      const std::size_t c = number(line, k + 1, n);
      if (c != std::string::npos && c < line.size() && line[c] == ')') {
        std::size_t e = c + 1;
        if (e < line.size() && line[e] == ' ') ++e;
        if (e < line.size() && line[e] == ':')
          line = where(n) + ": " + line.substr(std::min(line.size(), e + 2));
      }
    }
    if (line.size() > 400) line = line.substr(0, 400) + "...";
    if (!line.empty()) out += "  " + line + "\n";
  }
  return out;
}

/// The process's end where a dispatch outlives its time: said on standard error first.
class Watchdog {
 public:
  Watchdog(double seconds, const std::string& what) : what_(protocol::escape_bytes(what)) {
    thread_ = std::thread([this, seconds] {
      std::unique_lock<std::mutex> lock(mutex_);
      if (cv_.wait_for(lock, std::chrono::duration<double>(seconds), [this] { return done_; }))
        return;
      std::fprintf(stderr,
                   "oblique: %s did not finish within %g s (a loop that does not end?); the "
                   "driver cannot be stopped, so the process stops here (exit status %d)\n",
                   what_.c_str(), seconds, kHangExitStatus);
      std::fflush(stderr);
      std::_Exit(kHangExitStatus);
    });
  }
  ~Watchdog() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      done_ = true;
    }
    cv_.notify_all();
    thread_.join();
  }
  Watchdog(const Watchdog&) = delete;
  Watchdog& operator=(const Watchdog&) = delete;

 private:
  std::string what_;
  std::mutex mutex_;
  std::condition_variable cv_;
  bool done_ = false;
  std::thread thread_;
};

}  // namespace

std::array<float, kRequestVectors * 4> request_of(const oracle::DepthSample<float>& s,
                                                  VDirection v) {
  std::array<float, kRequestVectors * 4> out{};
  const Eigen::Matrix4d projection = s.projection.cast<double>();
  const Eigen::Matrix4d original = s.original.cast<double>();
  const Eigen::Matrix4d view = s.view.cast<double>();
  const Eigen::Matrix4d view_projection = projection * view;
  const Eigen::Matrix4d matrices[4] = {projection, projection.inverse(), original,
                                       original.inverse()};
  // (M' V)^-1 as V^-1 M'^-1: inverting the product itself, even in double, loses what a stiff M'
  // keeps in a tiny entry (a plane through the eye: M'34 ~ 1e-20 beside V's translation).
  const Eigen::Matrix4d world[4] = {view, view.inverse(), view_projection,
                                    view.inverse() * projection.inverse()};
  for (int k = 0; k < 4; ++k)
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c)
        out[static_cast<std::size_t>(88 + 16 * k + 4 * r + c)] = static_cast<float>(world[k](r, c));
  for (int k = 0; k < 4; ++k)
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c)
        out[static_cast<std::size_t>(16 * k + 4 * r + c)] = static_cast<float>(matrices[k](r, c));
  // The camera's near and far distances along its axis (M^-1 at the near face's and the far
  // face's centre), as an engine keeps them beside the matrix.
  const int axis = view_axis_sign(s.original, s.convention);
  const DepthRange range = clip_depth_range(s.convention);
  const bool reversed = s.convention == Convention::reversed_z;
  auto distance = [&](double ndc_z) {
    const Eigen::Vector4d p = matrices[3] * Eigen::Vector4d(0, 0, ndc_z, 1);
    return p.w() == 0 ? std::numeric_limits<double>::infinity() : axis * p.z() / p.w();
  };
  const double n = distance(reversed ? range.z_high : range.z_low);
  const double f = distance(reversed ? range.z_low : range.z_high);
  const bool infinite = !std::isfinite(f);
  // Unity's _ZBufferParams: LinearEyeDepth(d) = 1 / (z d + w) on a window depth d.
  double zp[4];
  if (!reversed) {
    zp[0] = infinite ? -std::numeric_limits<double>::infinity() : 1 - f / n;
    zp[1] = infinite ? std::numeric_limits<double>::infinity() : f / n;
    zp[2] = infinite ? -1 / n : zp[0] / f;
    zp[3] = infinite ? 1 / n : zp[1] / f;
  } else {
    zp[0] = infinite ? std::numeric_limits<double>::infinity() : -1 + f / n;
    zp[1] = 1;
    zp[2] = infinite ? 1 / n : zp[0] / f;
    zp[3] = infinite ? 0 : 1 / f;
  }
  const double params[4] = {1 / original(0, 0), 1 / original(1, 1), original(0, 2), original(1, 2)};
  // The pixel as a GPU hands it: its position in pixels from the target's lower left corner (the
  // centre, px + 1/2, exactly; or the sample's own NDC), rows counted from the top where v runs
  // down; a sample of no target is placed on a 1920 x 1080 one.
  const bool target = s.pixel.width > 0 && s.pixel.height > 0;
  const double width = target ? s.pixel.width : 1920, height = target ? s.pixel.height : 1080;
  double fx = (s.ndc_x + 1.0) / 2 * width, fy = (s.ndc_y + 1.0) / 2 * height;
  int column = static_cast<int>(std::clamp(std::floor(fx), 0.0, width - 1));
  int row = static_cast<int>(std::clamp(std::floor(fy), 0.0, height - 1));
  if (target && s.pixel.at_centre) {
    column = s.pixel.x;
    row = s.pixel.y;
    fx = column + 0.5;
    fy = row + 0.5;
  }
  if (v == VDirection::down) {
    fy = height - fy;
    row = static_cast<int>(height) - 1 - row;
  }
  const double rest[16] = {s.ndc_x,
                           s.ndc_y,
                           s.depth,
                           static_cast<double>(axis),
                           fx / width,
                           fy / height,
                           n,
                           f,
                           fx,
                           fy,
                           width,
                           height,
                           static_cast<double>(column),
                           static_cast<double>(row),
                           1 / width,
                           1 / height};
  for (int i = 0; i < 4; ++i) {
    out[static_cast<std::size_t>(64 + i)] = static_cast<float>(zp[i]);
    out[static_cast<std::size_t>(68 + i)] = static_cast<float>(params[i]);
  }
  for (int i = 0; i < 16; ++i) out[static_cast<std::size_t>(72 + i)] = static_cast<float>(rest[i]);
  return out;
}

bool perspective_along_z(Convention convention, const Matrix4<float>& m) {
  if (m(3, 0) != 0 || m(3, 1) != 0 || m(3, 3) != 0 || std::fabs(m(3, 2)) != 1) return false;
  if (m(0, 1) != 0 || m(1, 0) != 0 || m(0, 3) != 0 || m(1, 3) != 0 || m(2, 0) != 0 || m(2, 1) != 0)
    return false;
  const int axis = view_axis_sign(m, convention);
  return axis == static_cast<int>(m(3, 2)) && m(0, 0) != 0 && m(1, 1) != 0;
}

bool cannot_run_here(const std::string& error) {
  return error.rfind("no EGL", 0) == 0 || error.find("which is not installed") != std::string::npos;
}

struct ShaderRunner::State {
  RunnerOptions options;
  std::vector<ShaderFunction> functions;
  std::unique_ptr<raster::GlContext> gl;
  GLuint programs[kKinds][3] = {};
  bool perspective[kKinds] = {};
  bool pixel[kKinds] = {};  ///< reads uv, frag_coord or texel
  bool texel[kKinds] = {};
  VDirection v[kKinds] = {};
  std::string names[kKinds];
  GLuint buffers[2] = {0, 0};

  ~State() {
    if (!gl || !gl->make_current()) return;
    for (auto& row : programs)
      for (GLuint p : row)
        if (p) glDeleteProgram(p);
    if (buffers[0]) glDeleteBuffers(2, buffers);
  }

  Expected<GLuint> compile(const std::string& glsl, const std::string& path) {
    const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
    const char* text = glsl.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      GLint length = 0;
      glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
      std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
      glGetShaderInfoLog(shader, length, nullptr, log.data());
      glDeleteShader(shader);
      return Expected<GLuint>::failure("the shader did not compile:\n" +
                                       mapped_log(log.c_str(), path));
    }
    const GLuint program = glCreateProgram();
    glAttachShader(program, shader);
    glLinkProgram(program);
    glDeleteShader(shader);
    GLint linked = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &linked);
    if (!linked) {
      GLint length = 0;
      glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
      std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
      glGetProgramInfoLog(program, length, nullptr, log.data());
      glDeleteProgram(program);
      return Expected<GLuint>::failure("the shader did not link:\n" +
                                       mapped_log(log.c_str(), path));
    }
    return program;
  }
};

ShaderRunner::ShaderRunner(std::unique_ptr<State> state) : state_(std::move(state)) {}
ShaderRunner::~ShaderRunner() = default;

Expected<std::unique_ptr<ShaderRunner>> ShaderRunner::open(
    const std::vector<ShaderFunction>& functions, const RunnerOptions& options) {
  using Opened = Expected<std::unique_ptr<ShaderRunner>>;
  if (functions.empty()) return Opened::failure("no shader function to run");
  auto state = std::make_unique<State>();
  state->options = options;
  state->functions = functions;
  // The user's functions first: their mistakes are said before any device is looked for.
  struct Wrapped {
    int kind;
    std::string path, sources[3];
  };
  std::vector<Wrapped> wrapped;
  for (const ShaderFunction& f : functions) {
    if (kind_index(f.kind) < 0)
      return Opened::failure(std::string("a shader answers ") + kShaderKindsText + ", not " +
                             std::string(protocol::consumer_kind_name(f.kind)));
    const Expected<std::string> read = read_shader_file(f.path);
    if (!read) return Opened::failure(read.error());
    const std::string& source = *read;
    const Expected<std::string> user_defines = define_lines(f.defines);
    if (!user_defines) return Opened::failure(user_defines.error());
    const int k = kind_index(f.kind);
    state->names[k] = f.path + ":" + f.function;
    Wrapped w{k, f.path, {}};
    for (int c = 0; c < 3; ++c) {
      // The variant the preprocessor keeps in this convention, under the engine's defines.
      const Expected<std::string> kept = preprocessed(
          source, f.path, f.language, convention_defines(c, f.v, *user_defines, f.vectors),
          options.timeout_seconds);
      if (!kept) return Opened::failure(f.path + ": " + kept.error());
      // A depth function answers from its inputs: one that reaches the runner's buffers, memory
      // other invocations see or which invocation it is could write another request's answer.
      if (const auto beyond = reaches_beyond_its_inputs(tokens(without_comments(*kept))))
        return Opened::failure(f.path + ": " + *beyond +
                               ": a depth function answers from its inputs alone; declare no "
                               "buffers, images, shared memory or invocation ids");
      const Expected<Signature> sig = find_signature(*kept, f.function, f.language, f.kind);
      if (!sig) return Opened::failure(f.path + ": " + sig.error());
      for (const Parameter& p : sig->parameters) {
        state->perspective[k] = state->perspective[k] || shader::needs_perspective_camera(p.input);
        state->pixel[k] = state->pixel[k] || is_pixel_position(p.input);
        state->texel[k] = state->texel[k] || p.input == Input::texel;
      }
      state->v[k] = f.v;
      const std::string text =
          wrapped_source(source, f.path, *sig, f.language, c, f.v, *user_defines, f.vectors);
      if (f.language == Language::glsl) {
        // glslang first, under the limits: the driver compiles in this process.
        const Expected<Done> compiles = glsl_compiles(text, f.path, options.timeout_seconds);
        if (!compiles) return Opened::failure(f.path + ": " + compiles.error());
        w.sources[c] = text;
        continue;
      }
      Expected<std::string> glsl = hlsl_as_glsl(text, options.timeout_seconds);
      if (!glsl) return Opened::failure(f.path + ": " + glsl.error());
      w.sources[c] = *glsl;
    }
    wrapped.push_back(std::move(w));
  }
  Expected<std::unique_ptr<raster::GlContext>> gl = raster::GlContext::open(options.device);
  if (!gl) return Opened::failure(gl.error());
  state->gl = std::move(*gl);
  const raster::NoShaderCache no_cache;
  // What an interrupt says while the driver compiles (the tools say theirs, shader_tools.cpp).
  std::string names;
  for (const ShaderFunction& f : functions) names += (names.empty() ? "" : ", ") + f.path;
  protocol::set_interrupt_line("oblique: interrupted while compiling " + names +
                               " in the driver; nothing was judged");
  struct ClearLine {
    ~ClearLine() { protocol::set_interrupt_line(""); }
  } clear_line;
  for (const Wrapped& w : wrapped) {
    for (int c = 0; c < 3; ++c) {
      // The driver compiles in this process and cannot be stopped: past the time limit the
      // process ends, saying so (glslang compiled the same text within it just before).
      const Watchdog watchdog(std::max(options.timeout_seconds, kToolLeastSeconds),
                              "compiling " + w.path + " in the driver");
      Expected<GLuint> program = state->compile(w.sources[c], w.path);
      if (!program) return Opened::failure(w.path + ": " + program.error());
      state->programs[w.kind][c] = *program;
    }
  }
  glGenBuffers(2, state->buffers);
  return std::unique_ptr<ShaderRunner>(new ShaderRunner(std::move(state)));
}

const std::string& ShaderRunner::renderer() const {
  return state_->gl->renderer();
}

const std::vector<ShaderFunction>& ShaderRunner::functions() const {
  return state_->functions;
}

bool ShaderRunner::needs_perspective_camera(ConsumerKind kind) const {
  return state_->perspective[kind_index(kind)];
}

bool ShaderRunner::reads_pixel(ConsumerKind kind) const {
  return state_->pixel[kind_index(kind)];
}

bool ShaderRunner::reads_texel(ConsumerKind kind) const {
  return state_->texel[kind_index(kind)];
}

Expected<std::vector<std::vector<float>>> ShaderRunner::run(
    ConsumerKind kind, const std::vector<oracle::DepthSample<float>>& samples) {
  using Answers = Expected<std::vector<std::vector<float>>>;
  const int k = kind_index(kind);
  if (k < 0) return Answers::failure(std::string("a shader answers ") + kShaderKindsText + " only");
  if (!state_->programs[k][0])
    return Answers::failure("no shader function answers " +
                            std::string(protocol::consumer_kind_name(kind)));
  std::vector<std::vector<float>> out(samples.size());
  if (samples.empty()) return out;
  if (std::string error; !state_->gl->make_current(&error)) return Answers::failure(error);
  GLint most_groups = 0;
  glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 0, &most_groups);
  const std::size_t per_dispatch = static_cast<std::size_t>(most_groups) * kGroupSize;
  const int numbers = kind == ConsumerKind::linear_depth ? 1 : 3;
  // One dispatch per convention's program (each sample's own convention), in slices the device
  // takes.
  for (int c = 0; c < 3; ++c) {
    std::vector<std::size_t> at;
    for (std::size_t i = 0; i < samples.size(); ++i)
      if (static_cast<int>(samples[i].convention) == c) at.push_back(i);
    for (std::size_t from = 0; from < at.size(); from += per_dispatch) {
      const std::size_t count = std::min(per_dispatch, at.size() - from);
      const std::size_t padded = (count + kGroupSize - 1) / kGroupSize * kGroupSize;
      std::vector<float> requests(padded * kRequestVectors * 4);
      for (std::size_t j = 0; j < padded; ++j) {
        const auto r = request_of(samples[at[from + std::min(j, count - 1)]], state_->v[k]);
        std::copy(r.begin(), r.end(), requests.begin() + static_cast<long>(j * r.size()));
      }
      glBindBuffer(GL_SHADER_STORAGE_BUFFER, state_->buffers[0]);
      glBufferData(GL_SHADER_STORAGE_BUFFER,
                   static_cast<GLsizeiptr>(requests.size() * sizeof(float)), requests.data(),
                   GL_STREAM_DRAW);
      glBindBuffer(GL_SHADER_STORAGE_BUFFER, state_->buffers[1]);
      glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(padded * 4 * sizeof(float)),
                   nullptr, GL_STREAM_READ);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, state_->buffers[0]);
      glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, state_->buffers[1]);
      glUseProgram(state_->programs[k][c]);
      std::vector<float> answers(padded * 4);
      {
        const Watchdog watchdog(state_->options.timeout_seconds,
                                "the shader " + state_->names[k] + " (" + std::to_string(count) +
                                    (count == 1 ? " request" : " requests") + "; the first: " +
                                    oracle::wire::depth_request(kind, samples[at[from]]).line() +
                                    ")");
        glDispatchCompute(static_cast<GLuint>(padded / kGroupSize), 1, 1);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0,
                           static_cast<GLsizeiptr>(answers.size() * sizeof(float)), answers.data());
      }
      if (const GLenum e = glGetError(); e != GL_NO_ERROR) {
        char line[64];
        std::snprintf(line, sizeof line, "running the shader: GL error 0x%04x", e);
        return Answers::failure(line);
      }
      for (std::size_t j = 0; j < count; ++j)
        out[at[from + j]].assign(answers.begin() + static_cast<long>(4 * j),
                                 answers.begin() + static_cast<long>(4 * j + numbers));
    }
  }
  return out;
}

Consumers<float> shader_consumers(ShaderRunner& runner, const std::string& name,
                                  oracle::Sampling sampling) {
  Consumers<float> out;
  out.name = name;
  out.arithmetic = oracle::ConsumerArithmetic::gpu;
  out.sampling = sampling;
  bool perspective = false;
  for (const ShaderFunction& f : runner.functions()) {
    perspective = perspective || runner.needs_perspective_camera(f.kind);
    if (runner.reads_pixel(f.kind)) out.pixel_input = oracle::PixelInput::gpu;
    // A texel names a pixel: its centre is the only position it can be judged at.
    if (runner.reads_texel(f.kind)) out.sampling = oracle::Sampling::pixels;
    if (f.kind == ConsumerKind::view_position || f.kind == ConsumerKind::world_position) {
      const ConsumerKind kind = f.kind;
      (kind == ConsumerKind::view_position ? out.view_position : out.world_position) =
          [&runner, kind](const oracle::DepthSample<float>& s) {
            const auto a = runner.run(kind, {s});
            if (!a) throw std::runtime_error(a.error());
            return Vector3<float>(a->front()[0], a->front()[1], a->front()[2]);
          };
    } else {
      out.linear_depth = [&runner](const oracle::DepthSample<float>& s) {
        const auto a = runner.run(ConsumerKind::linear_depth, {s});
        if (!a) throw std::runtime_error(a.error());
        return a->front()[0];
      };
    }
  }
  if (perspective) out.accepts = perspective_along_z;
  return out;
}

Expected<std::vector<std::vector<float>>> answer_asks(
    ShaderRunner& runner, const std::vector<const oracle::ConsumerAsk<float>*>& asks) {
  using Answers = Expected<std::vector<std::vector<float>>>;
  std::vector<oracle::DepthSample<float>> samples[kKinds];
  std::vector<std::size_t> places[kKinds];
  Consumers<float> recording;
  ConsumerKind kind = ConsumerKind::view_position;
  recording.view_position = [&](const oracle::DepthSample<float>& s) {
    samples[0].push_back(s);
    kind = ConsumerKind::view_position;
    return Vector3<float>::Zero().eval();
  };
  recording.linear_depth = [&](const oracle::DepthSample<float>& s) {
    samples[1].push_back(s);
    kind = ConsumerKind::linear_depth;
    return 0.0f;
  };
  recording.world_position = [&](const oracle::DepthSample<float>& s) {
    samples[2].push_back(s);
    kind = ConsumerKind::world_position;
    return Vector3<float>::Zero().eval();
  };
  for (std::size_t i = 0; i < asks.size(); ++i) {
    if (kind_index(asks[i]->kind) < 0)
      return Answers::failure(std::string("a shader answers ") + kShaderKindsText + " only");
    (void)asks[i]->call(recording);
    places[kind_index(kind)].push_back(i);
  }
  std::vector<std::vector<float>> out(asks.size());
  for (int k = 0; k < kKinds; ++k) {
    if (samples[k].empty()) continue;
    const auto answers = runner.run(kShaderKinds[k], samples[k]);
    if (!answers) return Answers::failure(answers.error());
    for (std::size_t j = 0; j < places[k].size(); ++j) out[places[k][j]] = (*answers)[j];
  }
  return out;
}

}  // namespace oblique::shader
