// The reference scene of a case drawn on the headless OpenGL context (gl_context.h) through two
// matrices, and the pictures a report shows of it.
#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "oblique/raster/case_scene.h"

namespace oblique::raster {

namespace {

const char* const kVertexShader = R"(#version 450 core
layout(location = 0) in vec4 point;
layout(location = 1) in vec4 color;
uniform mat4 projection;
out vec4 shade;
void main() {
  gl_Position = projection * point;
  shade = color;
}
)";

const char* const kFragmentShader = R"(#version 450 core
in vec4 shade;
layout(location = 0) out vec4 color;
void main() { color = shade; }
)";

constexpr float kBackground[4] = {0.93f, 0.95f, 0.98f, 1};

/// The GL objects of one drawing, deleted when it ends.
struct Objects {
  GLuint program = 0, vertex_array = 0, buffers[2] = {0, 0};
  GLuint framebuffer = 0, colour = 0, depth = 0;
  ~Objects() {
    if (program) glDeleteProgram(program);
    if (buffers[0]) glDeleteBuffers(2, buffers);
    if (vertex_array) glDeleteVertexArrays(1, &vertex_array);
    if (colour) glDeleteRenderbuffers(1, &colour);
    if (depth) glDeleteRenderbuffers(1, &depth);
    if (framebuffer) glDeleteFramebuffers(1, &framebuffer);
  }
};

void draw_triangles(Objects& o, const std::vector<Eigen::Vector4f>& points,
                    const std::vector<Eigen::Vector4f>& colors) {
  if (points.empty()) return;
  glBindBuffer(GL_ARRAY_BUFFER, o.buffers[0]);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(points.size() * sizeof(Eigen::Vector4f)),
               points.data(), GL_STREAM_DRAW);
  glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, sizeof(Eigen::Vector4f), nullptr);
  glEnableVertexAttribArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, o.buffers[1]);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(colors.size() * sizeof(Eigen::Vector4f)),
               colors.data(), GL_STREAM_DRAW);
  glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, sizeof(Eigen::Vector4f), nullptr);
  glEnableVertexAttribArray(1);
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(points.size()));
}

std::uint8_t byte(double x) {
  return static_cast<std::uint8_t>(std::clamp(std::lround(x), 0L, 255L));
}

/// The two depth buffers as grey pictures on one scale: each depth drawn by its rank among the
/// depths of either (near bright, far dark), the background dark blue.
std::pair<report::Picture, report::Picture> depth_pictures(const Render& a, const Render& b,
                                                           bool reversed) {
  std::vector<float> drawn;
  for (const Render* r : {&a, &b})
    for (float d : r->depth)
      if (d != r->cleared) drawn.push_back(reversed ? -d : d);
  std::sort(drawn.begin(), drawn.end());
  drawn.erase(std::unique(drawn.begin(), drawn.end()), drawn.end());
  auto picture = [&](const Render& r) {
    report::Picture out(r.colour.width, r.colour.height, 0x1c2733ffu);
    for (int y = 0; y < out.height; ++y) {
      for (int x = 0; x < out.width; ++x) {
        const float d = r.depth[static_cast<std::size_t>(y) * out.width + x];
        if (d == r.cleared) continue;
        const float key = reversed ? -d : d;
        const double rank =
            drawn.size() < 2
                ? 0
                : double(std::lower_bound(drawn.begin(), drawn.end(), key) - drawn.begin()) /
                      double(drawn.size() - 1);
        const std::uint8_t g = byte(245 - 190 * rank);
        std::uint8_t* p = out.at(x, y);
        p[0] = p[1] = p[2] = g;
        p[3] = 255;
      }
    }
    return out;
  };
  return {picture(a), picture(b)};
}

/// A ring of radius `radius` around (cx, cy), two pixels wide, in `rgb`.
void ring(report::Picture& p, int cx, int cy, int radius, std::uint32_t rgb) {
  for (int y = cy - radius - 2; y <= cy + radius + 2; ++y) {
    for (int x = cx - radius - 2; x <= cx + radius + 2; ++x) {
      if (x < 0 || y < 0 || x >= p.width || y >= p.height) continue;
      const double r = std::hypot(x - cx, y - cy);
      if (std::abs(r - radius) > 1.0) continue;
      std::uint8_t* q = p.at(x, y);
      q[0] = static_cast<std::uint8_t>(rgb >> 16);
      q[1] = static_cast<std::uint8_t>(rgb >> 8);
      q[2] = static_cast<std::uint8_t>(rgb);
      q[3] = 255;
    }
  }
}

}  // namespace

Expected<Render> draw_mesh(GlContext& gl, const Mesh& mesh, const Eigen::Matrix4d& projection,
                           Convention convention, DepthBuffer buffer, int size) {
  const Eigen::Matrix4f matrix = projection.cast<float>();
  if (!matrix.allFinite())
    return Expected<Render>::failure(
        "the matrix does not fit float32 (an entry beyond its range or not finite)");
  if (std::string error; !gl.make_current(&error)) return Expected<Render>::failure(error);
  const NoShaderCache no_cache;
  Objects o;
  const Expected<unsigned> linked = link_program(kVertexShader, kFragmentShader);
  if (!linked) return Expected<Render>::failure("the scene's shaders: " + linked.error());
  o.program = *linked;
  glGenVertexArrays(1, &o.vertex_array);
  glGenBuffers(2, o.buffers);
  glGenFramebuffers(1, &o.framebuffer);
  glGenRenderbuffers(1, &o.colour);
  glGenRenderbuffers(1, &o.depth);
  glBindFramebuffer(GL_FRAMEBUFFER, o.framebuffer);
  glBindRenderbuffer(GL_RENDERBUFFER, o.colour);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, size, size);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, o.colour);
  glBindRenderbuffer(GL_RENDERBUFFER, o.depth);
  glRenderbufferStorage(
      GL_RENDERBUFFER,
      buffer == DepthBuffer::fixed24 ? GL_DEPTH_COMPONENT24 : GL_DEPTH_COMPONENT32F, size, size);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, o.depth);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    return Expected<Render>::failure("the scene's frame buffers are not complete");
  glViewport(0, 0, size, size);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  Render out;
  out.cleared = set_engine_depth(convention);
  glClearBufferfv(GL_COLOR, 0, kBackground);
  glUseProgram(o.program);
  glUniformMatrix4fv(glGetUniformLocation(o.program, "projection"), 1, GL_FALSE,
                     matrix.data());  // column-major
  glBindVertexArray(o.vertex_array);
  draw_triangles(o, mesh.points, mesh.colors);
  // The markers over everything, out of the depth buffer: seen wherever they are not clipped.
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  draw_triangles(o, mesh.overlay_points, mesh.overlay_colors);
  glDepthMask(GL_TRUE);
  const std::size_t count = static_cast<std::size_t>(size) * size;
  std::vector<std::uint8_t> colour(count * 4);
  std::vector<float> depth(count);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glReadPixels(0, 0, size, size, GL_RGBA, GL_UNSIGNED_BYTE, colour.data());
  glReadPixels(0, 0, size, size, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
  if (const std::string error = gl_error_after("drawing the scene"); !error.empty())
    return Expected<Render>::failure(error);
  // GL's rows are from the bottom; a picture's from the top.
  out.colour = report::Picture(size, size);
  out.depth.resize(count);
  for (int y = 0; y < size; ++y) {
    const std::size_t from = static_cast<std::size_t>(size - 1 - y) * size;
    std::copy(colour.begin() + static_cast<std::ptrdiff_t>(from * 4),
              colour.begin() + static_cast<std::ptrdiff_t>((from + size) * 4), out.colour.at(0, y));
    std::copy(depth.begin() + static_cast<std::ptrdiff_t>(from),
              depth.begin() + static_cast<std::ptrdiff_t>(from + size),
              out.depth.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(y) * size));
  }
  return out;
}

namespace {

/// The difference of two renders: `expected` faded, each pixel that differs in red.
report::Picture difference(const report::Picture& expected, const report::Picture& answered,
                           long& differing) {
  report::Picture out(expected.width, expected.height);
  differing = 0;
  for (int y = 0; y < out.height; ++y) {
    for (int x = 0; x < out.width; ++x) {
      const std::uint8_t* p = expected.at(x, y);
      const std::uint8_t* q = answered.at(x, y);
      std::uint8_t* d = out.at(x, y);
      if (std::equal(p, p + 4, q)) {
        const int grey = (p[0] + p[1] + p[2]) / 3;
        d[0] = d[1] = d[2] = static_cast<std::uint8_t>(200 + grey / 5);
      } else {
        ++differing;
        d[0] = 220, d[1] = 20, d[2] = 30;
      }
      d[3] = 255;
    }
  }
  return out;
}

/// Whether two pictures differ within 3 pixels of (x, y).
bool differs_near(const report::Picture& a, const report::Picture& b, int x, int y) {
  for (int v = y - 3; v <= y + 3; ++v)
    for (int u = x - 3; u <= x + 3; ++u)
      if (u >= 0 && v >= 0 && u < a.width && v < a.height &&
          !std::equal(a.at(u, v), a.at(u, v) + 4, b.at(u, v)))
        return true;
  return false;
}

/// `projection` seen zoomed in `factor` times around NDC (x0, y0): clip x and y scaled about the
/// point; z and w (what is clipped against C and the far plane) as they were.
Eigen::Matrix4d zoomed(const Eigen::Matrix4d& projection, double factor, double x0, double y0) {
  Eigen::Matrix4d out = projection;
  out.row(0) = factor * (projection.row(0) - x0 * projection.row(3));
  out.row(1) = factor * (projection.row(1) - y0 * projection.row(3));
  return out;
}

}  // namespace

Expected<CaseRenders> render_case(const Eigen::Matrix4d& m, const Eigen::Vector4d& c,
                                  const Eigen::Matrix4d& expected, const Eigen::Matrix4d& answer,
                                  Convention convention, const std::vector<Eigen::Vector4d>& hints,
                                  int size) {
  CaseRenders out;
  out.marks = disagreements(m, expected, answer, convention, hints);
  const NoShaderCache no_cache;
  Expected<std::unique_ptr<GlContext>> gl = GlContext::open(Device::software);
  if (!gl) return Expected<CaseRenders>::failure(gl.error());
  const DepthBuffer buffer =
      convention == Convention::reversed_z ? DepthBuffer::float32 : DepthBuffer::fixed24;
  // Draws the scene with out.marks through both, and says where each mark is on the screen
  // (through M: the side planes are M's) and whether the pictures differ there.
  Mesh mesh;
  std::vector<std::array<double, 2>> ndc;
  auto draw = [&]() -> Expected<Done> {
    mesh = reference_scene(m, c, convention, out.marks);
    if (mesh.points.empty())
      return Expected<Done>::failure(
          "M has no view volume to build a scene in (its near face or axis is not finite)");
    Expected<Render> e = draw_mesh(**gl, mesh, expected, convention, buffer, size);
    if (!e) return Expected<Done>::failure("the correct M': " + e.error());
    Expected<Render> a = draw_mesh(**gl, mesh, answer, convention, buffer, size);
    if (!a) return Expected<Done>::failure("the answer: " + a.error());
    out.expected = std::move(*e);
    out.answered = std::move(*a);
    out.difference = difference(out.expected.colour, out.answered.colour, out.differing);
    ndc.clear();
    out.mark_pixels.clear();
    out.mark_shown.clear();
    for (const Eigen::Vector4d& mark : out.marks) {
      const Eigen::Vector4d q = m * mark;
      const double x = q.x() / q.w(), y = q.y() / q.w();
      ndc.push_back({x, y});
      const int px = static_cast<int>(std::floor((x + 1) / 2 * size));
      const int py = size - 1 - static_cast<int>(std::floor((y + 1) / 2 * size));
      out.mark_pixels.push_back({px, py});
      out.mark_shown.push_back(differs_near(out.expected.colour, out.answered.colour, px, py));
    }
    return Done{};
  };
  if (const Expected<Done> drawn = draw(); !drawn)
    return Expected<CaseRenders>::failure(drawn.error());
  // A mark whose difference is too thin to see is zoomed into (x8, then x64); one that shows
  // nothing even there disagrees by less than a pixel: it is left out and the scene drawn again.
  std::vector<CaseRenders::Zoom> zooms;
  for (std::size_t k = 0; k < out.marks.size(); ++k) {
    if (out.mark_shown[k]) continue;
    for (int factor : {8, 64}) {
      const auto [x0, y0] = ndc[k];
      Expected<Render> ze =
          draw_mesh(**gl, mesh, zoomed(expected, factor, x0, y0), convention, buffer, size);
      Expected<Render> za =
          draw_mesh(**gl, mesh, zoomed(answer, factor, x0, y0), convention, buffer, size);
      if (!ze || !za) break;
      if (!differs_near(ze->colour, za->colour, size / 2, size / 2)) continue;
      CaseRenders::Zoom zoom;
      zoom.factor = factor;
      zoom.mark = static_cast<int>(k);
      zoom.expected = std::move(ze->colour);
      zoom.answered = std::move(za->colour);
      zoom.difference = difference(zoom.expected, zoom.answered, zoom.differing);
      for (report::Picture* p : {&zoom.expected, &zoom.answered, &zoom.difference})
        ring(*p, size / 2, size / 2, std::max(6, size / 30), 0x111111);
      zooms.push_back(std::move(zoom));
      out.mark_shown[k] = true;
      break;
    }
  }
  std::vector<Eigen::Vector4d> seen;
  std::vector<int> renumbered(out.marks.size(), -1);
  for (std::size_t k = 0; k < out.marks.size(); ++k) {
    if (!out.mark_shown[k]) continue;
    renumbered[k] = static_cast<int>(seen.size());
    seen.push_back(out.marks[k]);
  }
  out.unseen_marks = static_cast<int>(out.marks.size() - seen.size());
  if (out.unseen_marks > 0) {
    out.marks = seen;
    if (const Expected<Done> drawn = draw(); !drawn)
      return Expected<CaseRenders>::failure(drawn.error());
    for (CaseRenders::Zoom& zoom : zooms) {
      zoom.mark = renumbered[static_cast<std::size_t>(zoom.mark)];
      out.mark_shown[static_cast<std::size_t>(zoom.mark)] = true;
    }
  }
  out.zooms = std::move(zooms);
  const auto [de, da] =
      depth_pictures(out.expected, out.answered, convention == Convention::reversed_z);
  out.expected_depth = de;
  out.answered_depth = da;
  for (const auto& [x, y] : out.mark_pixels)
    for (report::Picture* p : {&out.expected.colour, &out.answered.colour, &out.difference})
      ring(*p, x, y, std::max(6, size / 30), 0x111111);
  return out;
}

}  // namespace oblique::raster
