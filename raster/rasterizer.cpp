// One frame's render and read-back on the headless OpenGL context (gl_context.h).
#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>

#include "oblique/oblique.h"
#include "oblique/projection.h"
#include "oblique/raster/raster.h"

namespace oblique::raster {

namespace {

const char* const kVertexShader = R"(#version 450 core
layout(location = 0) in vec4 point;
layout(location = 1) in uint sample_id;
uniform mat4 projection;
uniform int placed_by_id;  // 1: x and y from the sample's pixel (id - 1), depth from the point
uniform int size;
flat out uint id;
void main() {
  gl_Position = projection * point;
  if (placed_by_id != 0) {
    uint k = sample_id - 1u;
    vec2 pixel = vec2(float(k % uint(size)), float(k / uint(size))) + 0.5;
    gl_Position.xy = (pixel / float(size) * 2.0 - 1.0) * gl_Position.w;
  }
  gl_PointSize = 1.0;
  id = sample_id;
}
)";

const char* const kFragmentShader = R"(#version 450 core
flat in uint id;
layout(location = 0) out uint stored_id;
void main() { stored_id = id; }
)";

}  // namespace

struct Rasterizer::State {
  Options options;
  std::unique_ptr<GlContext> gl;
  std::string renderer;
  GLuint program = 0, vertex_array = 0, buffers[2] = {0, 0};
  GLuint framebuffer = 0, id_buffer = 0, depth_buffer = 0;
  GLint projection_at = -1, placed_by_id_at = -1, size_at = -1;
  DepthBuffer depth_format = DepthBuffer::fixed24;
  int allocated = 0;  ///< the buffers' size (0: none yet)

  ~State() {
    if (gl && gl->make_current()) {
      if (program) glDeleteProgram(program);
      if (buffers[0]) glDeleteBuffers(2, buffers);
      if (vertex_array) glDeleteVertexArrays(1, &vertex_array);
      if (id_buffer) glDeleteRenderbuffers(1, &id_buffer);
      if (depth_buffer) glDeleteRenderbuffers(1, &depth_buffer);
      if (framebuffer) glDeleteFramebuffers(1, &framebuffer);
    }
  }

  Expected<Done> start() {
    Expected<std::unique_ptr<GlContext>> opened = GlContext::open(options.device);
    if (!opened) return Expected<Done>::failure(opened.error());
    gl = std::move(*opened);
    renderer = gl->renderer();
    const NoShaderCache no_cache;
    return build();
  }

  Expected<Done> build() {
    const Expected<unsigned> linked = link_program(kVertexShader, kFragmentShader);
    if (!linked) return Expected<Done>::failure(linked.error());
    program = *linked;
    projection_at = glGetUniformLocation(program, "projection");
    placed_by_id_at = glGetUniformLocation(program, "placed_by_id");
    size_at = glGetUniformLocation(program, "size");
    glGenVertexArrays(1, &vertex_array);
    glGenBuffers(2, buffers);
    glGenFramebuffers(1, &framebuffer);
    glGenRenderbuffers(1, &id_buffer);
    glGenRenderbuffers(1, &depth_buffer);
    if (const std::string error = gl_error_after("setting up the frame"); !error.empty())
      return Expected<Done>::failure(error);
    return Done{};
  }

  /// The id and depth buffers for a `size` x `size` frame with a `format` depth buffer.
  Expected<Done> prepare(int size, DepthBuffer format) {
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    if (allocated == size && depth_format == format) return Done{};
    glBindRenderbuffer(GL_RENDERBUFFER, id_buffer);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_R32UI, size, size);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, id_buffer);
    glBindRenderbuffer(GL_RENDERBUFFER, depth_buffer);
    glRenderbufferStorage(
        GL_RENDERBUFFER,
        format == DepthBuffer::fixed24 ? GL_DEPTH_COMPONENT24 : GL_DEPTH_COMPONENT32F, size, size);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_buffer);
    allocated = 0;
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      return Expected<Done>::failure("the frame's buffers are not complete");
    allocated = size;
    depth_format = format;
    return Done{};
  }

  /// Draws `points` (sample ids `ids`) with M' = `answer` into a `size` x `size` frame and reads
  /// ids and depths back; `placed_by_id`: each point in the pixel of its id, its depth its own.
  Expected<Readback> draw(const std::vector<Eigen::Vector4f>& points,
                          const std::vector<std::uint32_t>& ids, int size,
                          const Eigen::Matrix4d& answer, Convention convention, DepthBuffer buffer,
                          bool placed_by_id) {
    State& s = *this;
    const Eigen::Matrix4f projection = answer.cast<float>();
    if (!projection.allFinite())
      return Expected<Readback>::failure(
          "the answer does not fit float32 (an entry beyond its range or not finite)");
    if (std::string error; !s.gl->make_current(&error)) return Expected<Readback>::failure(error);
    if (const Expected<Done> ready = s.prepare(size, buffer); !ready)
      return Expected<Readback>::failure(ready.error());
    glViewport(0, 0, size, size);
    glDisable(GL_MULTISAMPLE);
    glEnable(GL_PROGRAM_POINT_SIZE);
    set_engine_depth(convention);
    const GLuint no_id[4] = {0, 0, 0, 0};
    glClearBufferuiv(GL_COLOR, 0, no_id);
    glUseProgram(s.program);
    glUniformMatrix4fv(s.projection_at, 1, GL_FALSE, projection.data());  // column-major
    glUniform1i(s.placed_by_id_at, placed_by_id ? 1 : 0);
    glUniform1i(s.size_at, size);
    glBindVertexArray(s.vertex_array);
    glBindBuffer(GL_ARRAY_BUFFER, s.buffers[0]);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(points.size() * sizeof(Eigen::Vector4f)),
                 points.data(), GL_STREAM_DRAW);
    glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, sizeof(Eigen::Vector4f), nullptr);
    glEnableVertexAttribArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, s.buffers[1]);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(ids.size() * sizeof(std::uint32_t)),
                 ids.data(), GL_STREAM_DRAW);
    glVertexAttribIPointer(1, 1, GL_UNSIGNED_INT, sizeof(std::uint32_t), nullptr);
    glEnableVertexAttribArray(1);
    glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(points.size()));
    Readback out;
    const std::size_t count = static_cast<std::size_t>(size) * size;
    out.ids.resize(count);
    out.depths.resize(count);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glReadPixels(0, 0, size, size, GL_RED_INTEGER, GL_UNSIGNED_INT, out.ids.data());
    glReadPixels(0, 0, size, size, GL_DEPTH_COMPONENT, GL_FLOAT, out.depths.data());
    if (const std::string error = gl_error_after("rendering the frame"); !error.empty())
      return Expected<Readback>::failure(error);
    return out;
  }
};

Rasterizer::Rasterizer(std::unique_ptr<State> state) : state_(std::move(state)) {}
Rasterizer::~Rasterizer() = default;

const std::string& Rasterizer::renderer() const {
  return state_->renderer;
}
const Options& Rasterizer::options() const {
  return state_->options;
}

Expected<Readback> Rasterizer::render(const Frame& frame, const Eigen::Matrix4d& answer,
                                      Convention convention, DepthBuffer buffer) {
  std::vector<Eigen::Vector4f> points;
  std::vector<std::uint32_t> ids;
  points.reserve(frame.points.size());
  ids.reserve(frame.points.size());
  for (std::size_t k = 0; k < frame.points.size(); ++k) {
    if (!frame.placed[k]) continue;
    points.push_back(frame.points[k]);
    ids.push_back(static_cast<std::uint32_t>(k + 1));
  }
  return state_->draw(points, ids, frame.size, answer, convention, buffer, false);
}

Expected<AxisDepth> Rasterizer::axis_depth(const Eigen::Matrix4d& m, const Eigen::Vector4d& c,
                                           const Eigen::Matrix4d& answer, Convention convention,
                                           DepthBuffer buffer) {
  const int size = state_->options.size;
  const long count = static_cast<long>(size) * size;
  // The axis, M^-1 (0, 0, z, 1) from the near face to the far one, as homogeneous points with
  // w >= 0 (the far end a direction for an infinite projection); its kept part by C.
  const Eigen::Matrix4d inverse = m.inverse();
  const double z_near =
      convention == Convention::reversed_z ? 1 : clip_depth_range(convention).z_low;
  const double z_far = convention == Convention::reversed_z ? 0 : 1;
  Eigen::Vector4d a = inverse * Eigen::Vector4d(0, 0, z_near, 1);
  Eigen::Vector4d b = inverse * Eigen::Vector4d(0, 0, z_far, 1);
  if (a.w() < 0) a = -a;
  if (b.w() < 0) b = -b;
  const double ca = c.dot(a), cb = c.dot(b);
  if (ca < 0 && cb < 0)
    return Expected<AxisDepth>::failure("the view axis never enters the kept region");
  double s0 = 0, s1 = 1;
  if (ca < 0) s0 = ca / (ca - cb);
  if (cb < 0) s1 = ca / (ca - cb);
  std::vector<Eigen::Vector4f> points(static_cast<std::size_t>(count));
  std::vector<std::uint32_t> ids(static_cast<std::size_t>(count));
  for (long k = 0; k < count; ++k) {
    const double s = s0 + (s1 - s0) * (static_cast<double>(k) + 0.5) / static_cast<double>(count);
    Eigen::Vector4d p = (1 - s) * a + s * b;
    p /= p.cwiseAbs().maxCoeff();  // within float32's range whatever the distance
    points[static_cast<std::size_t>(k)] = p.cast<float>();
    ids[static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(k + 1);
  }
  const Expected<Readback> read = state_->draw(points, ids, size, answer, convention, buffer, true);
  if (!read) return Expected<AxisDepth>::failure(read.error());
  return measure_axis(*read, convention, buffer);
}

Expected<std::vector<std::optional<double>>> Rasterizer::stored_depths(
    const Eigen::Matrix4d& answer, const std::vector<Eigen::Vector4d>& points,
    Convention convention, DepthBuffer buffer) {
  using Depths = Expected<std::vector<std::optional<double>>>;
  const int size = state_->options.size;
  if (points.size() > static_cast<std::size_t>(size) * size)
    return Depths::failure("more points than the frame has pixels");
  std::vector<Eigen::Vector4f> drawn(points.size());
  std::vector<std::uint32_t> ids(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    const double largest = points[k].cwiseAbs().maxCoeff();
    drawn[k] = (largest > 0 ? Eigen::Vector4d(points[k] / largest) : points[k]).cast<float>();
    ids[k] = static_cast<std::uint32_t>(k + 1);
  }
  const Expected<Readback> read = state_->draw(drawn, ids, size, answer, convention, buffer, true);
  if (!read) return Depths::failure(read.error());
  std::vector<std::optional<double>> out(points.size());
  for (std::size_t k = 0; k < points.size(); ++k)
    if (read->ids[k] == k + 1) out[k] = read->depths[k];
  return out;
}

Result Rasterizer::check(const Eigen::Matrix4d& m, const Eigen::Vector4d& c,
                         const Eigen::Matrix4d& answer, Convention convention, DepthBuffer buffer,
                         std::uint64_t seed, int precision_bits) {
  return check(
      prepare_check(m, c, answer, convention, buffer, state_->options.size, seed, precision_bits));
}

Expected<Readback> Rasterizer::render(const PreparedCheck& p, double* render_seconds) {
  using Clock = std::chrono::steady_clock;
  if (!p.why.empty()) return Expected<Readback>::failure(p.why);
  if (p.frame.size != state_->options.size)
    return Expected<Readback>::failure("not rendered: a frame of " + std::to_string(p.frame.size) +
                                       " pixels a side, not " +
                                       std::to_string(state_->options.size));
  const auto start = Clock::now();
  Expected<Readback> readback = render(p.frame, p.answer, p.convention, p.buffer);
  if (render_seconds)
    *render_seconds = p.seconds + std::chrono::duration<double>(Clock::now() - start).count();
  if (!readback) return Expected<Readback>::failure("not rendered: " + readback.error());
  return readback;
}

Result Rasterizer::check(const PreparedCheck& p) {
  double render_seconds = 0;
  const Expected<Readback> readback = render(p, &render_seconds);
  if (!readback) {
    Result r;
    r.why = readback.error();
    return r;
  }
  return judge_prepared(p, *readback, render_seconds);
}

Expected<std::shared_ptr<Rasterizer>> Rasterizer::open(const Options& options) {
  using Opened = Expected<std::shared_ptr<Rasterizer>>;
  if (options.size < 16 || options.size > 4096)
    return Opened::failure("the frame's size must be within [16, 4096] pixels");
  auto state = std::make_unique<State>();
  state->options = options;
  if (const Expected<Done> started = state->start(); !started)
    return Opened::failure(started.error());
  std::shared_ptr<Rasterizer> out(new Rasterizer(std::move(state)));
  // The self-check: the core's answer on a fixed case (a tilted plane in front of a perspective
  // camera) passes in every convention and buffer, in a small frame.
  const Options asked = out->state_->options;
  out->state_->options.size = 128;
  for (const Convention convention : all_conventions) {
    const Eigen::Matrix4d m = perspective<double>(1.0, 1.25, 0.5, 200.0, convention);
    const Eigen::Vector4d c(0.3, -0.8, -0.5, -2.0);
    const ObliqueResult<double> answer = apply<double>(m, c, convention);
    for (const DepthBuffer buffer : {DepthBuffer::fixed24, DepthBuffer::float32}) {
      const Result r = out->check(m, c, answer.projection, convention, buffer, 7);
      if (r.outcome != Outcome::pass)
        return Opened::failure("the renderer (" + out->renderer() +
                               ") failed its self-check, the core's answer on a fixed case in " +
                               std::string(convention_name(convention)) + ", " +
                               std::string(depth_buffer_name(buffer)) + ": " + r.why);
    }
  }
  out->state_->options = asked;
  return out;
}

}  // namespace oblique::raster
