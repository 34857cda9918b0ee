// check_consumers(): the code around the matrix (oblique::Consumers) against the
// consumer properties (oblique/properties/consumers.h), one RapidCheck run per property, for
// float, double and long double.
#include <functional>
#include <sstream>

#include "oblique/oblique.h"
#include "oblique/properties/consumer_generators.h"
#include "oblique/report/report_files.h"
#include "oblique/testing/harness.h"

namespace oblique::testing {

namespace {

/// Fails the current case with the finding, and keeps the report the run writes if it is the
/// last (most shrunk) failure.
void fail(const std::string& consumer, const properties::ConsumerFinding& finding,
          const std::string& inputs,
          std::function<std::string(report::ReportFiles&, const std::string&)> pictures) {
  const std::string name(properties::consumer_check_name(finding.check));
  std::ostringstream report;
  report << "# Counterexample: " << name << "\n\n"
         << "`" << consumer << "` violates **" << name << "**.\n\n"
         << "## What was found\n\n"
         << properties::describe(finding) << "\n\n"
         << "## The inputs\n\n"
         << inputs << "\n"
         << "Numbers print so that they read back to the same value; matrices are row by row, "
            "planes keep P . x >= 0. The properties and their bounds: docs/consumers.md.\n";
  tally().consumer_failure = report.str();
  tally().consumer_pictures = std::move(pictures);
  tally().failure.reset();
  RC_FAIL(consumer + " violates " + properties::describe(finding) + "\n" + inputs);
}

template <class T>
struct ObliqueCase {
  generators::Case<T> base;
  Matrix4<T> oblique;
};

/// Counts the finding; fails the case when it is violated (with the case's pictures when it has
/// an oblique matrix: M's volume, C, the core's M' and the finding's points).
template <class T = double>
void judged(const std::string& consumer, const properties::ConsumerFinding& finding,
            const std::string& inputs, const ObliqueCase<T>* c = nullptr) {
  if (!finding.judged) {
    ++tally().left_out[finding.detail];
    return;
  }
  ++tally().applied[std::string(properties::consumer_check_name(finding.check))];
  if (finding.holds) return;
  std::function<std::string(report::ReportFiles&, const std::string&)> pictures;
  if (c) {
    Counterexample ce =
        properties::make_counterexample(c->base.matrix, c->base.plane, c->base.convention);
    ce.implementation = "the core's M', given to " + consumer;
    properties::set_result(ce, c->oblique);
    properties::set_views(ce, Problem<T>(c->base.matrix, c->base.plane, c->base.convention),
                          &c->oblique);
    pictures = [ce, finding, consumer](report::ReportFiles& files, const std::string& stem) {
      return properties::stage_consumer_pictures(
          files, ce, stem,
          std::string(properties::consumer_check_name(finding.check)) + " (" + consumer + ")",
          finding.points_what.empty() ? std::string("nothing") : finding.points_what,
          finding.points);
    };
  }
  fail(consumer, finding, inputs, std::move(pictures));
}

/// A case of the contract and the core's answer to it (cases without one are discarded).
template <class T>
ObliqueCase<T> oblique_case(const Contract& contract, const std::string& consumer) {
  const generators::Case<T> c = *generators::valid_case_for<T>(contract);
  const ObliqueResult<T> result = apply<T>(c.matrix, c.plane, c.convention);
  RC_PRE(result.status == Status::ok);
  count_case(c);
  ++tally().implementations[consumer];
  return {c, result.projection};
}

template <class T>
std::string case_text(const ObliqueCase<T>& c) {
  return "- convention: " + std::string(convention_name(c.base.convention)) + " (family " +
         std::string(generators::family_name(c.base.family)) + ", place " +
         std::string(generators::place_name(c.base.place)) +
         ")\n- M: " + properties::numbers_text(c.base.matrix) +
         "\n- C: " + properties::numbers_text(c.base.plane) +
         "\n- M' (the core's answer, what the consumer was given): " +
         properties::numbers_text(c.oblique) + "\n";
}

}  // namespace

inline namespace OBLIQUE_EIGEN_LAYOUT {

template <class T>
void check_consumers(const oblique::Consumers<T>& consumers, const Contract& given) {
  const Contract contract =
      resolved(given, generators::every_convention(), properties::StatusContract::exact, false);
  const std::string who = consumers.name;
  bool any = false;

  if (consumers.view_position || consumers.linear_depth) {
    for (int pass = 0; pass < 2; ++pass) {
      if ((pass == 0 && !consumers.view_position) || (pass == 1 && !consumers.linear_depth))
        continue;
      any = true;
      const auto check = pass == 0 ? properties::ConsumerCheck::view_position
                                   : properties::ConsumerCheck::linear_depth;
      run(
          [=] {
            const ObliqueCase<T> c = oblique_case<T>(contract, who);
            const Vector4<T> point =
                *generators::kept_point<T>(c.base.matrix, c.base.plane, c.base.convention);
            const DepthBuffer buffer =
                *generators::detail::category({DepthBuffer::fixed24, DepthBuffer::float32});
            const auto sample = properties::depth_sample<T>(c.oblique, c.base.matrix,
                                                            c.base.convention, buffer, point);
            RC_PRE(sample.has_value());
            const std::string inputs =
                case_text(c) +
                "- buffer: " + (buffer == DepthBuffer::fixed24 ? "fixed24" : "float32") +
                "\n- the point: " + properties::numbers_text(point) + "\n- the sample: NDC x " +
                protocol::format_number(sample->ndc_x) + ", y " +
                protocol::format_number(sample->ndc_y) + ", window depth " +
                protocol::format_number(sample->depth) + " (stored " +
                std::to_string(sample->stored) + ")\n";
            if (pass == 0) {
              judged(who,
                     properties::judge_view_position(*sample, consumers.view_position(*sample)),
                     inputs, &c);
            } else {
              judged(who, properties::judge_linear_depth(*sample, consumers.linear_depth(*sample)),
                     inputs, &c);
            }
          },
          Coverage::valid, std::string(properties::consumer_check_name(check)), contract);
    }
  }

  if (consumers.culling_planes) {
    any = true;
    for (const auto check : {properties::ConsumerCheck::culling_keeps_visible,
                             properties::ConsumerCheck::culling_near_is_c}) {
      run(
          [=] {
            const ObliqueCase<T> c = oblique_case<T>(contract, who);
            const FrustumPlanes<T> planes = consumers.culling_planes(c.oblique, c.base.convention);
            const std::string inputs = case_text(c) + "- the planes: left " +
                                       properties::numbers_text(planes.left) + ", right " +
                                       properties::numbers_text(planes.right) + ", bottom " +
                                       properties::numbers_text(planes.bottom) + ", top " +
                                       properties::numbers_text(planes.top) + ", near " +
                                       properties::numbers_text(planes.near_plane) + ", far " +
                                       properties::numbers_text(planes.far_plane) + "\n";
            for (const auto& f : properties::judge_culling_planes<T>(
                     c.base.matrix, c.base.plane, c.base.convention, c.oblique, planes)) {
              if (f.check == check) judged(who, f, inputs, &c);
            }
          },
          Coverage::valid, std::string(properties::consumer_check_name(check)), contract);
    }
  }

  if (consumers.camera_plane) {
    any = true;
    for (const auto check : {properties::ConsumerCheck::plane_on_surface,
                             properties::ConsumerCheck::plane_kept_side}) {
      run(
          [=] {
            const consumer_cases::PassPlaneCase<T> c = *generators::pass_plane_case<T>();
            ++tally().implementations[who];
            ++tally().places[consumer_cases::pass_kind_name(c.kind)];
            const Vector4<T> answer = consumers.camera_plane(c.pass_view, c.kept_plane);
            const std::string inputs =
                std::string("- pass: ") + consumer_cases::pass_kind_name(c.kind) +
                "\n- main view: " + properties::numbers_text(c.main_view) +
                "\n- pass view: " + properties::numbers_text(c.pass_view) +
                "\n- world plane kept: " + properties::numbers_text(c.kept_plane) +
                "\n- answered: " + properties::numbers_text(answer) + "\n";
            for (const auto& f : properties::judge_camera_plane<T>(
                     c.pass_view, c.kept_plane, c.surface_points, c.front_point, answer)) {
              if (f.check == check) judged(who, f, inputs);
            }
          },
          Coverage::none, std::string(properties::consumer_check_name(check)), contract);
    }
  }

  if (consumers.mirror_view) {
    any = true;
    run(
        [=] {
          const Matrix4<T> view = *generators::rigid_view<T>();
          const Vector4<T> plane = *generators::world_plane<T>();
          ++tally().implementations[who];
          const Matrix4<T> answer = consumers.mirror_view(view, plane);
          judged(who, properties::judge_mirror_view<T>(view, plane, answer),
                 "- view: " + properties::numbers_text(view) +
                     "\n- mirror plane: " + properties::numbers_text(plane) +
                     "\n- answered: " + properties::numbers_text(answer) + "\n");
        },
        Coverage::none, "mirror_view", contract);
  }

  if (consumers.portal_view) {
    any = true;
    run(
        [=] {
          const Matrix4<T> view = *generators::rigid_view<T>();
          const Matrix4<T> frame = *generators::portal_frame<T>();
          const Matrix4<T> linked = *generators::portal_frame<T>();
          ++tally().implementations[who];
          const Matrix4<T> answer = consumers.portal_view(view, frame, linked);
          judged(who, properties::judge_portal_view<T>(view, frame, linked, answer),
                 "- view: " + properties::numbers_text(view) +
                     "\n- frame: " + properties::numbers_text(frame) +
                     "\n- linked frame: " + properties::numbers_text(linked) +
                     "\n- answered: " + properties::numbers_text(answer) + "\n");
        },
        Coverage::none, "portal_view", contract);
  }

  if (consumers.corners) {
    any = true;
    run(
        [=] {
          const ObliqueCase<T> c = oblique_case<T>(contract, who);
          const std::vector<Vector3<T>> corners =
              consumers.corners(c.oblique, c.base.matrix, c.base.convention);
          std::string listed;
          for (const auto& p : corners) listed += " " + properties::numbers_text(p);
          judged(who,
                 properties::judge_corners<T>(c.base.matrix, c.base.plane, c.base.convention,
                                              c.oblique, corners),
                 case_text(c) + "- the corners:" + listed + "\n", &c);
        },
        Coverage::valid, "corners_contain_kept", contract);
  }

  if (!any) ADD_FAILURE() << who << ": oblique::Consumers gives no function to check";
}

template void check_consumers<float>(const oblique::Consumers<float>&, const Contract&);
template void check_consumers<double>(const oblique::Consumers<double>&, const Contract&);
template void check_consumers<long double>(const oblique::Consumers<long double>&, const Contract&);

}  // namespace OBLIQUE_EIGEN_LAYOUT

}  // namespace oblique::testing
