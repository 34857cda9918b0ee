// oblique check's consumers: the code around the matrix a scene names, asked for each rendered
// pass (of the core's references, or of the user's program with --impl) and judged by the
// consumer properties, on the pass's own matrix, views and plane.
#include <algorithm>
#include <cmath>
#include <random>

#include "oblique/client/consumer_program.h"
#include "oblique/mistakes/consumer_mistakes.h"
#include "oblique/oracle/consumer_cases.h"
#include "oblique/protocol/shell_text.h"
#include "oblique/run/tally.h"
#include "oblique/scene/check.h"

namespace oblique::scene {

namespace {

/// The picks of a pass's samples: the same every run, so a scene's verdict is repeatable.
constexpr std::uint64_t kSampleSeed = 20261204;

/// The request kinds a scene consumer asks.
std::vector<protocol::ConsumerKind> kinds_of(SceneConsumer c) {
  using K = protocol::ConsumerKind;
  switch (c) {
    case SceneConsumer::reconstruction: return {K::view_position, K::linear_depth};
    case SceneConsumer::culling: return {K::culling_planes};
    case SceneConsumer::cascades: return {K::corners};
    case SceneConsumer::camera_plane: return {K::camera_plane};
    case SceneConsumer::pass_view: return {K::mirror_view, K::portal_view};
  }
  return {};
}

}  // namespace

template <class T>
std::vector<ConsumerResult> judge_consumers(const Scene& scene, const SurfaceCheck& pass,
                                            const Consumers<T>& who) {
  const Matrix4<T> m = pass.camera_projection.template cast<T>();
  const Vector4<T> c = pass.plane_in_camera.template cast<T>();
  const Surface& surface = scene.surfaces[pass.path.back()];
  std::vector<ConsumerResult> out;
  for (const SceneConsumer consumer : scene.consumers) {
    ConsumerResult r;
    r.consumer = consumer;
    const oracle::Explain<T> explain = mistakes::explain_consumer<T>;
    std::string not_applicable;  // why a property says nothing of this pass's matrix
    const oracle::Settle settle = [&r, &not_applicable](const oracle::ConsumerFinding& f,
                                                        const std::string& inputs, bool) {
      if (!f.judged && f.unjudged == oracle::ConsumerFinding::Unjudged::not_applicable) {
        not_applicable = f.detail;  // (corners of an infinite camera's unbounded kept region)
        return;
      }
      if (!f.judged) {
        ++r.left_out_why[f.detail];
        return;
      }
      ++r.judged;
      if (std::isfinite(f.ratio)) r.worst_ratio = std::max(r.worst_ratio, f.ratio);
      r.depth_waste = std::max(r.depth_waste, f.depth_waste);
      if (!f.holds && !r.violation) {
        r.violation = f;
        r.inputs = inputs;
      }
    };
    std::mt19937_64 engine(kSampleSeed);
    const oracle::Pick pick = [&engine](int lo, int hi) {
      return std::uniform_int_distribution<int>(lo, hi - 1)(engine);
    };
    Consumers<T> only = settings_of(who);
    int rounds = 1;
    switch (consumer) {
      case SceneConsumer::reconstruction:
        only.view_position = who.view_position;
        only.linear_depth = who.linear_depth;
        // (A world position is asked through pass views of the round's own, not the scene's.)
        only.world_position = who.world_position;
        rounds = kConsumerSamples;
        break;
      case SceneConsumer::culling: only.culling_planes = who.culling_planes; break;
      case SceneConsumer::cascades: only.corners = who.corners; break;
      case SceneConsumer::camera_plane: {
        rounds = 0;
        oracle::consumer_cases::PassPlaneCase<T> p;
        p.kind = surface.kind == SurfaceKind::mirror   ? oracle::consumer_cases::PassKind::mirror
                 : surface.kind == SurfaceKind::portal ? oracle::consumer_cases::PassKind::portal
                                                       : oracle::consumer_cases::PassKind::clip;
        p.main_view = pass.parent_view.template cast<T>();
        p.pass_view = pass.view.template cast<T>();
        p.kept_plane = pass.kept_plane.template cast<T>();
        oracle::consumer_cases::plane_samples(p.kept_plane, pick, p.surface_points, p.front_point);
        oracle::consumer_cases::ask_camera_plane(who, p, settle, explain);
        break;
      }
      case SceneConsumer::pass_view:
        rounds = 0;
        if (surface.kind == SurfaceKind::mirror) {
          oracle::consumer_cases::ask_mirror_view<T>(who, pass.parent_view.template cast<T>(),
                                                     surface.plane().template cast<T>(), settle,
                                                     explain);
        } else if (surface.kind == SurfaceKind::portal) {
          oracle::consumer_cases::ask_portal_view<T>(
              who, pass.parent_view.template cast<T>(), surface.portal_frame.template cast<T>(),
              surface.linked_frame.template cast<T>(), settle, explain);
        } else {
          r.note = "a clip pass renders with the main view";
        }
        break;
    }
    for (int i = 0; i < rounds; ++i)
      oracle::consumer_round<T>(m, c, scene.convention, only, pick, settle, explain);
    // Nothing asked of it applies to this pass: said as a clip pass's note is, not left out.
    if (r.judged == 0 && r.left_out_why.empty() && !not_applicable.empty() && r.note.empty())
      r.note = not_applicable;
    out.push_back(std::move(r));
  }
  return out;
}

template std::vector<ConsumerResult> judge_consumers<float>(const Scene&, const SurfaceCheck&,
                                                            const Consumers<float>&);
template std::vector<ConsumerResult> judge_consumers<double>(const Scene&, const SurfaceCheck&,
                                                             const Consumers<double>&);
template std::vector<ConsumerResult> judge_consumers<long double>(const Scene&, const SurfaceCheck&,
                                                                  const Consumers<long double>&);

namespace {

template <class T>
Expected<Done> ask_program(const Scene& scene, SceneCheck& check, const std::string& command,
                           double timeout_seconds, oracle::Sampling sampling) {
  std::vector<protocol::ConsumerKind> kinds;
  for (const SceneConsumer c : scene.consumers)
    for (const protocol::ConsumerKind k : kinds_of(c)) kinds.push_back(k);
  client::ConsumerProgram<T> program(
      command, std::chrono::milliseconds(static_cast<long>(timeout_seconds * 1000)),
      check.impl_order);
  Consumers<T> asked = program.consumers(kinds, command);
  asked.mirror_design = scene.mirror_design;  // the design the scene's engine declares
  asked.sampling = sampling;
  try {
    for (SurfaceCheck& s : check.surfaces) {
      if (s.render) s.impl_consumers = judge_consumers<T>(scene, s, asked);
    }
  } catch (const client::Failure& failure) {
    program.stop();
    std::string why = "the implementation's consumers: " + failure.what +
                      " (request: " + failure.request.substr(0, 200) + ")";
    if (!failure.lines.empty())
      why += "; it wrote: " + protocol::escape_bytes(failure.lines.front().substr(0, 200));
    return Expected<Done>::failure(why);
  }
  // As verify: lines beyond one answer per request mean each answer was judged against another
  // request, so no verdict stands.
  if (const std::vector<std::string> extra = program.finish(); !extra.empty())
    return Expected<Done>::failure(
        "the implementation's consumers wrote lines beyond one answer per request (" +
        std::to_string(program.answered()) + " answer lines read before; the first extra line: " +
        protocol::escape_bytes(extra.front().substr(0, 200)) + ")");
  return Done{};
}

}  // namespace

Scene reconstruction_only(const Scene& scene) {
  Scene only = scene;
  only.consumers.clear();
  for (const SceneConsumer c : scene.consumers)
    if (c == SceneConsumer::reconstruction) only.consumers.push_back(c);
  return only;
}

Expected<Done> judge_shader_consumers(const Scene& scene, SceneCheck& check,
                                      const Consumers<float>& shader) {
  const Scene only = reconstruction_only(scene);
  if (only.consumers.empty())
    return Expected<Done>::failure(
        "--shader answers the scene's reconstruction consumer, and the scene names none: add "
        "\"reconstruction\" to its \"consumers\"");
  check.impl_shader = shader.name;
  check.impl_precision = protocol::Precision::float32;
  try {
    for (SurfaceCheck& s : check.surfaces) {
      if (s.render) s.impl_consumers = judge_consumers<float>(only, s, shader);
    }
  } catch (const std::runtime_error& e) {
    return Expected<Done>::failure(std::string("the shader could not be run: ") + e.what());
  }
  return Done{};
}

ConsumerCoverage consumer_coverage(const Scene& scene, const SceneCheck& check, bool impl) {
  ConsumerCoverage out;
  long rendered = 0;
  for (const SurfaceCheck& s : check.surfaces) rendered += s.render ? 1 : 0;
  run::Advice advice;
  advice.claimant = "the scene names";
  advice.unit = "answer";
  advice.rounds = "rendered passes";
  advice.none_drawn = "no pass was rendered to ask it on (each surface's reason is above)";
  advice.more = "move the camera or the surfaces so that one renders";
  advice.judge_left_out = "ask in a wider precision (--precision)";
  advice.applicable = "add a surface it applies to";
  advice.leave_out = [](const run::Kind& k) { return "leave " + k.name + " out of \"consumers\""; };
  for (const SceneConsumer consumer : scene.consumers) {
    const run::Kind kind{"consumer", std::string(scene_consumer_name(consumer))};
    run::Tally tally;  // one a consumer: the reasons said are its own
    for (const SurfaceCheck& s : check.surfaces) {
      if (!s.render) continue;
      for (const ConsumerResult& r : impl ? s.impl_consumers : s.consumers) {
        if (r.consumer != consumer) continue;
        if (!r.note.empty()) {
          tally.not_applicable({kind}, r.note);
          continue;
        }
        tally.judged({kind}, r.judged);
        for (const auto& [reason, n] : r.left_out_why) tally.left_out({kind}, reason, true, n);
      }
    }
    for (std::string& line : run::unjudged(tally, {kind}, rendered, advice))
      out.unjudged.push_back(std::move(line));
    if (const std::string partly =
            run::partly_judged(tally, {kind}, run::kLeftOutWarning, /*with_axis=*/false);
        !partly.empty())
      out.partly += (out.partly.empty() ? "" : ", ") + partly;
  }
  return out;
}

Expected<Done> judge_implementation_consumers(const Scene& scene, SceneCheck& check,
                                              const std::string& command, double timeout_seconds,
                                              oracle::Sampling sampling) {
  if (scene.consumers.empty()) return Done{};
  switch (check.impl_precision) {
    case protocol::Precision::float32:
      return ask_program<float>(scene, check, command, timeout_seconds, sampling);
    case protocol::Precision::float64: break;
    case protocol::Precision::long_double:
      return ask_program<long double>(scene, check, command, timeout_seconds, sampling);
  }
  return ask_program<double>(scene, check, command, timeout_seconds, sampling);
}

}  // namespace oblique::scene
