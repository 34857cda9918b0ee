// The consumer rounds (consumers.h): a round's asks planned from its picks (the request, the
// in-process call and the judge of each), a round asked of an in-process Consumers, and the
// core's references as a Consumers; compiled once for float, double and long double.
#include "oblique/oracle/consumers.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "oblique/oblique.h"
#include "oblique/oracle/consumer_cases.h"
#include "oblique/oracle/consumer_wire.h"
#include "oblique/protocol/numbers.h"
#include "oblique/references/kept_region.h"
#include "oblique/references/pass_camera.h"

namespace oblique::oracle {

namespace {

using protocol::ConsumerKind;

template <class T>
ConsumerAsk<T> depth_ask(ConsumerKind kind, const DepthSample<T>& s, const std::string& inputs,
                         ConsumerArithmetic arithmetic) {
  ConsumerAsk<T> a;
  a.kind = kind;
  a.request = [kind, s] { return wire::depth_request(kind, s); };
  if (kind == ConsumerKind::view_position) {
    a.call = [s](const Consumers<T>& c) { return wire::numbers_of(c.view_position(s)); };
    a.judge = [s, inputs, arithmetic](const std::vector<T>& v, const Settle& settle) {
      const Vector3<T> answer = wire::vector3(v);
      settle(judge_view_position(s, answer, arithmetic),
             inputs + "- answered: " + numbers_text(answer) + "\n", true);
    };
  } else if (kind == ConsumerKind::world_position) {
    a.call = [s](const Consumers<T>& c) { return wire::numbers_of(c.world_position(s)); };
    a.judge = [s, inputs, arithmetic](const std::vector<T>& v, const Settle& settle) {
      const Vector3<T> answer = wire::vector3(v);
      settle(judge_world_position(s, answer, arithmetic),
             inputs + "- the pass camera's view (world to camera): " + numbers_text(s.view) +
                 "\n- answered: " + numbers_text(answer) + "\n",
             true);
    };
  } else {
    a.call = [s](const Consumers<T>& c) { return std::vector<T>{c.linear_depth(s)}; };
    a.judge = [s, inputs, arithmetic](const std::vector<T>& v, const Settle& settle) {
      settle(judge_linear_depth(s, v.front(), arithmetic),
             inputs + "- answered: " + protocol::format_number(v.front()) + "\n", true);
    };
  }
  return a;
}

template <class T>
ConsumerAsk<T> culling_ask(const Matrix4<T>& m, const Vector4<T>& c, Convention convention,
                           const Matrix4<T>& mo, const std::string& base) {
  ConsumerAsk<T> a;
  a.kind = ConsumerKind::culling_planes;
  a.request = [mo, convention] { return wire::culling_request(mo, convention); };
  a.call = [mo, convention](const Consumers<T>& k) {
    return wire::numbers_of(k.culling_planes(mo, convention));
  };
  a.judge = [m, c, convention, mo, base](const std::vector<T>& v, const Settle& settle) {
    const FrustumPlanes<T> p = wire::planes(v);
    const std::string inputs =
        base + "- the planes: left " + numbers_text(p.left) + ", right " + numbers_text(p.right) +
        ", bottom " + numbers_text(p.bottom) + ", top " + numbers_text(p.top) + ", near " +
        numbers_text(p.near_plane) + ", far " + numbers_text(p.far_plane) + "\n";
    for (const auto& f : judge_culling_planes(m, c, convention, mo, p)) settle(f, inputs, true);
  };
  return a;
}

template <class T>
ConsumerAsk<T> corners_ask(const Matrix4<T>& m, const Vector4<T>& c, Convention convention,
                           const Matrix4<T>& mo, const std::string& base) {
  ConsumerAsk<T> a;
  a.kind = ConsumerKind::corners;
  a.request = [mo, m, convention] { return wire::corners_request(mo, m, convention); };
  a.call = [mo, m, convention](const Consumers<T>& k) {
    return wire::numbers_of(k.corners(mo, m, convention));
  };
  a.judge = [m, c, convention, mo, base](const std::vector<T>& v, const Settle& settle) {
    const std::vector<Vector3<T>> corners = wire::points(v);
    std::string listed;
    for (const auto& x : corners) listed += " " + numbers_text(x);
    settle(judge_corners(m, c, convention, mo, corners), base + "- the corners:" + listed + "\n",
           true);
  };
  return a;
}

template <class T>
ConsumerAsk<T> camera_plane_ask(const oracle::consumer_cases::PassPlaneCase<T>& p) {
  ConsumerAsk<T> a;
  a.kind = ConsumerKind::camera_plane;
  a.request = [p] {
    return wire::view_and_plane_request(ConsumerKind::camera_plane, p.pass_view, p.kept_plane);
  };
  a.call = [p](const Consumers<T>& k) {
    return wire::numbers_of(k.camera_plane(p.pass_view, p.kept_plane));
  };
  a.judge = [p](const std::vector<T>& v, const Settle& settle) {
    const Vector4<T> answer = wire::vector4(v);
    const std::string inputs = std::string("- pass: ") +
                               std::string(oracle::consumer_cases::pass_kind_name(p.kind)) +
                               "\n- main view: " + numbers_text(p.main_view) +
                               "\n- pass view: " + numbers_text(p.pass_view) +
                               "\n- world plane kept: " + numbers_text(p.kept_plane) +
                               "\n- answered: " + numbers_text(answer) + "\n";
    for (const auto& f :
         judge_camera_plane(p.pass_view, p.kept_plane, p.surface_points, p.front_point, answer))
      settle(f, inputs, false);
  };
  return a;
}

template <class T>
ConsumerAsk<T> mirror_view_ask(const Matrix4<T>& view, const Vector4<T>& mirror,
                               MirrorDesign design) {
  ConsumerAsk<T> a;
  a.kind = ConsumerKind::mirror_view;
  a.request = [view, mirror] {
    return wire::view_and_plane_request(ConsumerKind::mirror_view, view, mirror);
  };
  a.call = [view, mirror](const Consumers<T>& k) {
    return wire::numbers_of(k.mirror_view(view, mirror));
  };
  a.judge = [view, mirror, design](const std::vector<T>& v, const Settle& settle) {
    const Matrix4<T> answer = wire::matrix4(v);
    settle(judge_mirror_view(view, mirror, answer, design),
           "- view: " + numbers_text(view) + "\n- mirror plane: " + numbers_text(mirror) +
               "\n- answered: " + numbers_text(answer) + "\n",
           false);
  };
  return a;
}

template <class T>
ConsumerAsk<T> portal_view_ask(const Matrix4<T>& view, const Matrix4<T>& frame,
                               const Matrix4<T>& linked) {
  ConsumerAsk<T> a;
  a.kind = ConsumerKind::portal_view;
  a.request = [view, frame, linked] { return wire::portal_request(view, frame, linked); };
  a.call = [view, frame, linked](const Consumers<T>& k) {
    return wire::numbers_of(k.portal_view(view, frame, linked));
  };
  a.judge = [view, frame, linked](const std::vector<T>& v, const Settle& settle) {
    const Matrix4<T> answer = wire::matrix4(v);
    settle(judge_portal_view(view, frame, linked, answer),
           "- view: " + numbers_text(view) + "\n- frame: " + numbers_text(frame) +
               "\n- linked frame: " + numbers_text(linked) +
               "\n- answered: " + numbers_text(answer) + "\n",
           false);
  };
  return a;
}

/// Asks an in-process Consumers and judges its answer.
template <class T>
void ask_and_judge(const ConsumerAsk<T>& a, const Consumers<T>& consumers, const Settle& settle,
                   const Explain<T>& explain) {
  judge_explained(a, a.call(consumers), settle, explain);
}

}  // namespace

template <class T>
void judge_explained(const ConsumerAsk<T>& ask, const std::vector<T>& answer, const Settle& settle,
                     const Explain<T>& explain) {
  if (!explain) {
    ask.judge(answer, settle);
    return;
  }
  ask.judge(answer, [&](const ConsumerFinding& f, const std::string& inputs, bool about) {
    if (!f.judged || f.holds) {
      settle(f, inputs, about);
      return;
    }
    ConsumerFinding explained = f;
    explain(ask, answer, explained);
    settle(explained, inputs, about);
  });
}

template <class T>
std::vector<ConsumerAsk<T>> consumer_asks(const Matrix4<T>& m, const Vector4<T>& c,
                                          Convention convention, const Consumers<T>& consumers,
                                          const Pick& pick, const Settle& settle) {
  std::vector<ConsumerAsk<T>> asks;
  const bool depth = consumers.view_position || consumers.linear_depth || consumers.world_position;
  const bool needs_oblique = depth || consumers.culling_planes || consumers.corners;
  // A case none of `checks` can be judged on: one finding left out for each of them.
  auto left_out = [&settle](
                      std::initializer_list<std::pair<bool, ConsumerCheck>> checks,
                      const std::string& why,
                      ConsumerFinding::Unjudged unjudged = ConsumerFinding::Unjudged::undecided) {
    for (const auto& [asked, check] : checks) {
      if (!asked) continue;
      ConsumerFinding none;
      none.check = check;
      none.judged = false;
      none.unjudged = unjudged;
      none.detail = why;
      settle(none, "", false);
    }
  };
  if (needs_oblique && consumers.accepts && !consumers.accepts(convention, m)) {
    left_out({{bool(consumers.view_position), ConsumerCheck::view_position},
              {bool(consumers.linear_depth), ConsumerCheck::linear_depth},
              {bool(consumers.world_position), ConsumerCheck::world_position},
              {bool(consumers.culling_planes), ConsumerCheck::culling_keeps_visible},
              {bool(consumers.culling_planes), ConsumerCheck::culling_near_is_c},
              {bool(consumers.corners), ConsumerCheck::corners_contain_kept}},
             "refused by accepts (" + consumers.name + ")");
  } else if (needs_oblique) {
    const ObliqueResult<T> result = apply<T>(m, c, convention);
    if (result.status != Status::ok) {
      const bool culling = bool(consumers.culling_planes);
      left_out({{bool(consumers.view_position), ConsumerCheck::view_position},
                {bool(consumers.linear_depth), ConsumerCheck::linear_depth},
                {bool(consumers.world_position), ConsumerCheck::world_position},
                {culling, ConsumerCheck::culling_keeps_visible},
                {culling, ConsumerCheck::culling_near_is_c},
                {bool(consumers.corners), ConsumerCheck::corners_contain_kept}},
               "no oblique matrix for M and C (" + std::string(status_code(result.status)) + ")",
               ConsumerFinding::Unjudged::unclaimed);
    } else {
      const Matrix4<T>& mo = result.projection;
      const std::string base =
          "- convention: " + std::string(convention_name(convention)) +
          "\n- M: " + numbers_text(m) + "\n- C: " + numbers_text(c) +
          "\n- M' (the core's answer, what the consumer was given): " + numbers_text(mo) + "\n";
      if (depth) {
        Vector4<T> point = oracle::consumer_cases::kept_point<T>(m, c, convention, pick);
        const DepthBuffer buffer = pick(0, 2) ? DepthBuffer::float32 : DepthBuffer::fixed24;
        auto s = depth_sample(mo, m, convention, buffer, point);
        // A vertex of the region rounds to either side of its plane, and a point pushed toward
        // infinity can pass behind the eye: moved inward step by step (to the centre at most),
        // it is still a point of the region, near where it was, with a sample to judge.
        for (int k : {20, 10, 4, 1, 0}) {
          if (s) break;
          point =
              oracle::consumer_cases::toward_centre(m, c, convention, point, std::ldexp(1.0L, -k));
          s = depth_sample(mo, m, convention, buffer, point);
        }
        if (!s) {
          left_out({{bool(consumers.view_position), ConsumerCheck::view_position},
                    {bool(consumers.linear_depth), ConsumerCheck::linear_depth},
                    {bool(consumers.world_position), ConsumerCheck::world_position}},
                   "the point leaves no depth sample (behind the eye or outside [0, 1])");
        } else {
          // Read at a pixel of a target of a real size (or where the point projects, asked so),
          // the pixel handed as the consumer reads it.
          s = at_pixel(*s, oracle::consumer_cases::render_target(pick), consumers.sampling);
          s->ndc_error = ndc_error_of<T>(consumers.pixel_input, consumers.arithmetic);
          const std::string where =
              "pixel (" + std::to_string(s->pixel.x) + ", " + std::to_string(s->pixel.y) +
              ") of a " + std::to_string(s->pixel.width) + " x " + std::to_string(s->pixel.height) +
              " target (rows from the bottom), " +
              (consumers.sampling == Sampling::pixels ? "at its centre" : "off its centre") +
              (s->ndc_error != 0 ? ", handed as a GPU hands it (the ray within " +
                                       protocol::format_number(s->ndc_error) + " in NDC x and y)"
                                 : "");
          const std::string inputs = base + "- buffer: " + std::string(depth_buffer_name(buffer)) +
                                     "\n- the point: " + numbers_text(point) +
                                     "\n- the sample: NDC x " + protocol::format_number(s->ndc_x) +
                                     ", y " + protocol::format_number(s->ndc_y) + ", " + where +
                                     ", window depth " + protocol::format_number(s->depth) +
                                     " (stored " + std::to_string(s->stored) + ")\n";
          if (consumers.view_position)
            asks.push_back(
                depth_ask(ConsumerKind::view_position, *s, inputs, consumers.arithmetic));
          if (consumers.linear_depth)
            asks.push_back(depth_ask(ConsumerKind::linear_depth, *s, inputs, consumers.arithmetic));
          if (consumers.world_position) {
            // Drawn only where asked: the other kinds' rounds keep their picks.
            s->view = oracle::consumer_cases::pass_view<T>(pick);
            asks.push_back(
                depth_ask(ConsumerKind::world_position, *s, inputs, consumers.arithmetic));
          }
        }
      }
      if (consumers.culling_planes) asks.push_back(culling_ask(m, c, convention, mo, base));
      if (consumers.corners) asks.push_back(corners_ask(m, c, convention, mo, base));
    }
  }
  if (consumers.camera_plane)
    asks.push_back(camera_plane_ask(oracle::consumer_cases::pass_plane_case<T>(pick)));
  if (consumers.mirror_view) {
    const Matrix4<T> view = oracle::consumer_cases::rigid_view<T>(pick);
    asks.push_back(mirror_view_ask(view, oracle::consumer_cases::world_plane<T>(pick),
                                   consumers.mirror_design));
  }
  if (consumers.portal_view) {
    const Matrix4<T> view = oracle::consumer_cases::rigid_view<T>(pick);
    const Matrix4<T> frame = oracle::consumer_cases::portal_frame<T>(pick);
    asks.push_back(portal_view_ask(view, frame, oracle::consumer_cases::portal_frame<T>(pick)));
  }
  return asks;
}

template <class T>
void consumer_round(const Matrix4<T>& m, const Vector4<T>& c, Convention convention,
                    const Consumers<T>& consumers, const Pick& pick, const Settle& settle,
                    const Explain<T>& explain) {
  for (const ConsumerAsk<T>& a : consumer_asks(m, c, convention, consumers, pick, settle))
    ask_and_judge(a, consumers, settle, explain);
}

}  // namespace oblique::oracle

namespace oblique::oracle::consumer_cases {

template <class T>
void ask_camera_plane(const Consumers<T>& consumers, const PassPlaneCase<T>& p,
                      const oracle::Settle& settle, const oracle::Explain<T>& explain) {
  oracle::ask_and_judge(oracle::camera_plane_ask(p), consumers, settle, explain);
}

template <class T>
void ask_mirror_view(const Consumers<T>& consumers, const Matrix4<T>& view,
                     const Vector4<T>& mirror, const oracle::Settle& settle,
                     const oracle::Explain<T>& explain) {
  oracle::ask_and_judge(oracle::mirror_view_ask(view, mirror, consumers.mirror_design), consumers,
                        settle, explain);
}

template <class T>
void ask_portal_view(const Consumers<T>& consumers, const Matrix4<T>& view, const Matrix4<T>& frame,
                     const Matrix4<T>& linked, const oracle::Settle& settle,
                     const oracle::Explain<T>& explain) {
  oracle::ask_and_judge(oracle::portal_view_ask(view, frame, linked), consumers, settle, explain);
}

#define OBLIQUE_CONSUMER_ASKS(T)                                                           \
  template void ask_camera_plane(const Consumers<T>&, const PassPlaneCase<T>&,             \
                                 const oracle::Settle&, const oracle::Explain<T>&);        \
  template void ask_mirror_view(const Consumers<T>&, const Matrix4<T>&, const Vector4<T>&, \
                                const oracle::Settle&, const oracle::Explain<T>&);         \
  template void ask_portal_view(const Consumers<T>&, const Matrix4<T>&, const Matrix4<T>&, \
                                const Matrix4<T>&, const oracle::Settle&,                  \
                                const oracle::Explain<T>&);
OBLIQUE_CONSUMER_ASKS(float)
OBLIQUE_CONSUMER_ASKS(double)
OBLIQUE_CONSUMER_ASKS(long double)
#undef OBLIQUE_CONSUMER_ASKS

}  // namespace oblique::oracle::consumer_cases

namespace oblique::oracle {

template <class T>
Consumers<T> reference_consumers() {
  Consumers<T> c;
  c.name = "core_references";
  c.view_position = [](const DepthSample<T>& s) {
    return view_position(s.projection, s.ndc_x, s.ndc_y, s.depth, s.convention);
  };
  c.linear_depth = [](const DepthSample<T>& s) {
    return linear_depth(s.projection, s.ndc_x, s.ndc_y, s.depth, s.convention,
                        view_axis_sign(s.original, s.convention));
  };
  c.world_position = [](const DepthSample<T>& s) {
    return world_position(s.projection, s.view, s.ndc_x, s.ndc_y, s.depth, s.convention);
  };
  c.culling_planes = [](const Matrix4<T>& m, Convention k) { return frustum_planes(m, k); };
  c.camera_plane = [](const Matrix4<T>& view, const Vector4<T>& plane) {
    return plane_in_camera(view, plane);
  };
  c.mirror_view = [](const Matrix4<T>& view, const Vector4<T>& plane) {
    return oblique::mirror_view(view, plane);
  };
  c.portal_view = [](const Matrix4<T>& view, const Matrix4<T>& frame, const Matrix4<T>& linked) {
    return oblique::portal_view(view, frame, linked);
  };
  c.corners = [](const Matrix4<T>& m, const Matrix4<T>& original, Convention k) {
    std::vector<Vector3<T>> out;
    for (const auto& v : kept_region_vertices(original, near_plane(m, k), k))
      out.push_back(v.template head<3>());
    return out;
  };
  return c;
}

#define OBLIQUE_CONSUMER_INSTANCES(T)                                                              \
  template Consumers<T> reference_consumers<T>();                                                  \
  template void consumer_round(const Matrix4<T>&, const Vector4<T>&, Convention,                   \
                               const Consumers<T>&, const Pick&, const Settle&,                    \
                               const Explain<T>&);                                                 \
  template void judge_explained(const ConsumerAsk<T>&, const std::vector<T>&, const Settle&,       \
                                const Explain<T>&);                                                \
  template std::vector<ConsumerAsk<T>> consumer_asks(const Matrix4<T>&, const Vector4<T>&,         \
                                                     Convention, const Consumers<T>&, const Pick&, \
                                                     const Settle&);

OBLIQUE_CONSUMER_INSTANCES(float)
OBLIQUE_CONSUMER_INSTANCES(double)
OBLIQUE_CONSUMER_INSTANCES(long double)

}  // namespace oblique::oracle
