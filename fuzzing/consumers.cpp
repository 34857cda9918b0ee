// oblique::fuzzing::test_consumers() (oblique/fuzzing.h): the code around the matrix on decoded
// cases, judged by the consumer properties; compiled once for float, double and long double.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "oblique/fuzzing.h"
#include "oblique/fuzzing/driver.h"
#include "oblique/oblique.h"
#include "oblique/properties/consumer_cases.h"

namespace oblique::fuzzing {

namespace {

/// Counts a finding; on a violation prints it with the inputs and aborts.
void settle(const std::string& consumer, const properties::ConsumerFinding& finding,
            const std::string& inputs) {
  if (!finding.judged) {
    ++counts().left_out[finding.detail];
    return;
  }
  ++counts().judged;
  if (finding.holds) return;
  std::fprintf(stderr, "oblique: %s violates %s\n%s", consumer.c_str(),
               properties::describe(finding).c_str(), inputs.c_str());
  std::fflush(stderr);
  std::abort();
}

}  // namespace

inline namespace OBLIQUE_EIGEN_LAYOUT {

template <class T>
int test_consumers(const std::uint8_t* data, std::size_t size, const Consumers<T>& consumers,
                   const Contract& given) {
  const Contract contract =
      resolved(given, generators::every_convention(), properties::StatusContract::exact, false);
  const FuzzCase c = decode(data, size, contract.conventions);
  if (describing()) describe(c);
  // The choices: the input read from its end, two bytes per pick.
  std::vector<std::uint8_t> tail(data, data + size);
  std::reverse(tail.begin(), tail.end());
  ByteReader choices(tail.data(), tail.size());
  auto pick = [&choices](int lo, int hi) {
    const unsigned v = choices.byte() | (unsigned(choices.byte()) << 8);
    return lo + static_cast<int>(v % static_cast<unsigned>(hi - lo));
  };
  const std::string& who = consumers.name;

  Matrix4<T> m;
  Vector4<T> plane;
  for (int i = 0; i < 4; ++i) {
    plane(i) = narrow<T>(c.plane(i));
    for (int j = 0; j < 4; ++j) m(i, j) = narrow<T>(c.matrix(i, j));
  }
  const bool needs_oblique = consumers.view_position || consumers.linear_depth ||
                             consumers.culling_planes || consumers.corners;
  const ObliqueResult<T> result =
      needs_oblique ? apply<T>(m, plane, c.convention) : ObliqueResult<T>{};
  if (needs_oblique && result.status == Status::ok) {
    const Matrix4<T>& mo = result.projection;
    const std::string base =
        "  convention: " + std::string(convention_name(c.convention)) +
        "\n  M: " + properties::numbers_text(m) + "\n  C: " + properties::numbers_text(plane) +
        "\n  M' (the core's answer, given): " + properties::numbers_text(mo) + "\n";
    if (consumers.view_position || consumers.linear_depth) {
      const Vector4<T> point = consumer_cases::kept_point<T>(m, plane, c.convention, pick);
      const DepthBuffer buffer = pick(0, 2) ? DepthBuffer::float32 : DepthBuffer::fixed24;
      if (const auto s = properties::depth_sample(mo, m, c.convention, buffer, point)) {
        const std::string inputs = base + "  sample: NDC x " + protocol::format_number(s->ndc_x) +
                                   ", y " + protocol::format_number(s->ndc_y) + ", window depth " +
                                   protocol::format_number(s->depth) + " (" +
                                   (buffer == DepthBuffer::fixed24 ? "fixed24" : "float32") +
                                   ", stored " + std::to_string(s->stored) + ")\n";
        if (consumers.view_position)
          settle(who, properties::judge_view_position(*s, consumers.view_position(*s)), inputs);
        if (consumers.linear_depth)
          settle(who, properties::judge_linear_depth(*s, consumers.linear_depth(*s)), inputs);
      }
    }
    if (consumers.culling_planes) {
      const FrustumPlanes<T> p = consumers.culling_planes(mo, c.convention);
      const std::string inputs = base + "  planes: left " + properties::numbers_text(p.left) +
                                 ", right " + properties::numbers_text(p.right) + ", bottom " +
                                 properties::numbers_text(p.bottom) + ", top " +
                                 properties::numbers_text(p.top) + ", near " +
                                 properties::numbers_text(p.near_plane) + ", far " +
                                 properties::numbers_text(p.far_plane) + "\n";
      for (const auto& f : properties::judge_culling_planes(m, plane, c.convention, mo, p))
        settle(who, f, inputs);
    }
    if (consumers.corners) {
      const std::vector<Vector3<T>> corners = consumers.corners(mo, m, c.convention);
      std::string inputs = base + "  corners:";
      for (const auto& x : corners) inputs += " " + properties::numbers_text(x);
      settle(who, properties::judge_corners(m, plane, c.convention, mo, corners), inputs + "\n");
    }
  } else if (needs_oblique) {
    ++counts().left_out["no oblique matrix for M and C (" +
                        std::string(status_code(result.status)) + ")"];
  }
  if (consumers.camera_plane) {
    const consumer_cases::PassPlaneCase<T> p = consumer_cases::pass_plane_case<T>(pick);
    const Vector4<T> answer = consumers.camera_plane(p.pass_view, p.kept_plane);
    const std::string inputs = std::string("  pass: ") + consumer_cases::pass_kind_name(p.kind) +
                               "\n  pass view: " + properties::numbers_text(p.pass_view) +
                               "\n  world plane kept: " + properties::numbers_text(p.kept_plane) +
                               "\n  answered: " + properties::numbers_text(answer) + "\n";
    for (const auto& f : properties::judge_camera_plane(p.pass_view, p.kept_plane, p.surface_points,
                                                        p.front_point, answer))
      settle(who, f, inputs);
  }
  if (consumers.mirror_view) {
    const Matrix4<T> view = consumer_cases::rigid_view<T>(pick);
    const Vector4<T> mirror = consumer_cases::world_plane<T>(pick);
    const Matrix4<T> answer = consumers.mirror_view(view, mirror);
    settle(who, properties::judge_mirror_view(view, mirror, answer),
           "  view: " + properties::numbers_text(view) +
               "\n  mirror plane: " + properties::numbers_text(mirror) +
               "\n  answered: " + properties::numbers_text(answer) + "\n");
  }
  if (consumers.portal_view) {
    const Matrix4<T> view = consumer_cases::rigid_view<T>(pick);
    const Matrix4<T> frame = consumer_cases::portal_frame<T>(pick);
    const Matrix4<T> linked = consumer_cases::portal_frame<T>(pick);
    const Matrix4<T> answer = consumers.portal_view(view, frame, linked);
    settle(who, properties::judge_portal_view(view, frame, linked, answer),
           "  view: " + properties::numbers_text(view) + "\n  frame: " +
               properties::numbers_text(frame) + "\n  linked: " + properties::numbers_text(linked) +
               "\n  answered: " + properties::numbers_text(answer) + "\n");
  }
  return 0;
}

#define OBLIQUE_FUZZING_CONSUMERS(T)                                                    \
  template int test_consumers<T>(const std::uint8_t*, std::size_t, const Consumers<T>&, \
                                 const Contract&);
OBLIQUE_FUZZING_CONSUMERS(float)
OBLIQUE_FUZZING_CONSUMERS(double)
OBLIQUE_FUZZING_CONSUMERS(long double)
#undef OBLIQUE_FUZZING_CONSUMERS

}  // namespace OBLIQUE_EIGEN_LAYOUT
}  // namespace oblique::fuzzing
