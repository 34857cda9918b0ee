// check_on_rasterizer(): an implementation's answers to the contract's cases drawn on the
// rasterizer (oblique::raster) and judged there, one RapidCheck run, for float and double.
#include "oblique/testing/raster.h"

#include <limits>
#include <map>
#include <memory>
#include <string>
#include <utility>

#include "oblique/oblique.h"
#include "oblique/oracle/consumers.h"
#include "oblique/raster/raster_report.h"
#include "oblique/testing/harness.h"

namespace oblique::testing {

namespace {

/// The rasterizer of `settings`, opened once a process (its self-checks run then).
const Expected<std::shared_ptr<raster::Rasterizer>>& rasterizer_for(
    const RasterSettings& settings) {
  static std::map<std::pair<raster::Device, int>, Expected<std::shared_ptr<raster::Rasterizer>>>
      opened;
  const auto key = std::make_pair(settings.device, settings.size);
  auto found = opened.find(key);
  if (found == opened.end()) {
    raster::Options options;
    options.device = settings.device;
    options.size = settings.size;
    found = opened.emplace(key, raster::Rasterizer::open(options)).first;
  }
  return found->second;
}

/// The report of a case the rasterizer failed, or could not judge.
template <class T>
std::string raster_markdown(const cases::Case<T>& c, const Implementation<T>& impl,
                            const Matrix4<T>& answer, const raster::Result& r,
                            const std::string& renderer, DepthBuffer buffer, int size,
                            std::uint64_t seed) {
  const bool failed = r.outcome == raster::Outcome::fail;
  std::string md =
      std::string(failed ? "# Counterexample: the rasterizer ("
                         : "# Inconclusive: the rasterizer (") +
      impl.name + ", " + (std::is_same_v<T, float> ? "float" : "double") + ")\n\n" +
      (failed ? impl.name + "'s answer, drawn on " + renderer + ", fails: " + r.why + ".\n"
              : "The renderer (" + renderer + ") tripped a self-check: " + r.why +
                    ". This is no verdict about " + impl.name + ".\n") +
      "\n## The case\n\n- family `" + std::string(cases::family_name(c.family)) + "`, place `" +
      std::string(cases::place_name(c.place)) + "`, convention " +
      std::string(convention_name(c.convention)) + "\n- depth buffer " +
      std::string(depth_buffer_name(buffer)) + ", frame " + std::to_string(size) + " x " +
      std::to_string(size) + ", seed " + std::to_string(seed) +
      "\n- M: " + oracle::numbers_text(c.matrix) + "\n- C: " + oracle::numbers_text(c.plane) +
      "\n- the answer: " + oracle::numbers_text(answer) + "\n";
  return md;
}

}  // namespace

inline namespace OBLIQUE_EIGEN_LAYOUT {

template <class T>
void check_on_rasterizer(const Implementation<T>& impl, const Contract& given,
                         const RasterSettings& settings) {
  const Contract contract = resolved(given, impl.conventions, impl.status_contract(), false);
  if (!serves_conventions(impl, contract)) return;
  if (settings.buffers.empty()) {
    ADD_FAILURE() << "oblique::testing: RasterSettings names no depth buffer to draw into";
    return;
  }
  if (!(settings.size >= 16 && settings.size <= 4096)) {
    ADD_FAILURE() << "oblique::testing: RasterSettings::size must be within [16, 4096] pixels, not "
                  << settings.size;
    return;
  }
  const auto& opened = rasterizer_for(settings);
  if (!opened) {
    if (opened.error().rfind("no EGL", 0) == 0)
      GTEST_SKIP() << "oblique::testing: the rasterizer cannot run here: " << opened.error();
    ADD_FAILURE() << "oblique::testing: inconclusive, the rasterizer cannot judge (no verdict "
                     "about "
                  << impl.name << "): " << opened.error();
    return;
  }
  const std::shared_ptr<raster::Rasterizer> rasterizer = *opened;
  run(
      [=] {
        const cases::Case<T> c = *cases::valid_case_for<T>(contract);
        count_generated(c);
        const std::vector<run::Kind> kinds = run::kinds_of(c);
        if (!impl.accepts(c.convention, c.matrix)) {
          count_left_out(kinds, "", impl.name);
          return;
        }
        const Eigen::Matrix4d m = c.matrix.template cast<double>();
        const Eigen::Vector4d plane = c.plane.template cast<double>();
        // The judge's reference is the core's answer in double; cases without one have nothing
        // to draw against (the properties judge their statuses).
        if (apply<double>(m, plane, c.convention).status != Status::ok) {
          count_left_out(kinds, "no answer to judge against");
          return;
        }
        const Answer<T> outcome = impl.run(c.matrix, c.plane, c.convention);
        if (outcome.status != Status::ok) {
          count_left_out(kinds, impl.name + " answered a status (the properties judge it)");
          return;
        }
        const Eigen::Matrix4d answer = outcome.projection.template cast<double>();
        if (!answer.template cast<float>().allFinite()) {
          count_left_out(kinds, "the answer does not fit float32");
          return;
        }
        count_judged(c);
        const DepthBuffer buffer = *rc::gen::elementOf(settings.buffers);
        const std::uint64_t seed = *rc::gen::inRange<std::uint64_t>(1, std::uint64_t{1} << 32);
        ++tally().implementations[impl.name];
        ++tally().applied["drawn into " + std::string(depth_buffer_name(buffer))];
        const raster::Result r = rasterizer->check(m, plane, answer, c.convention, buffer, seed,
                                                   std::numeric_limits<T>::digits);
        if (r.outcome == raster::Outcome::pass) return;
        tally().failure.reset();
        tally().markdown_failure = raster_markdown(
            c, impl, outcome.projection, r, rasterizer->renderer(), buffer, settings.size, seed);
        tally().markdown_pictures = nullptr;
        if (r.rendered) {
          tally().markdown_pictures = [r, size = settings.size, m, plane, answer,
                                       convention = c.convention](report::ReportFiles& files,
                                                                  const std::string& stem) {
            return raster::stage_raster_finding(files, stem, r, size, m, plane, answer, convention);
          };
        }
        if (r.outcome == raster::Outcome::fail)
          fail_case(impl.name + " fails on the rasterizer (" + rasterizer->renderer() + ", " +
                    std::string(depth_buffer_name(buffer)) + "): " + r.why);
        fail_case("inconclusive, no verdict about " + impl.name + ": the rasterizer (" +
                  rasterizer->renderer() + ") could not judge: " + r.why);
      },
      Coverage::valid, "rasterizer", contract);
}

template void check_on_rasterizer<float>(const Implementation<float>&, const Contract&,
                                         const RasterSettings&);
template void check_on_rasterizer<double>(const Implementation<double>&, const Contract&,
                                          const RasterSettings&);

}  // namespace OBLIQUE_EIGEN_LAYOUT

}  // namespace oblique::testing
