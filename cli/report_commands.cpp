// `oblique report accuracy` and `oblique report depth`: the measurement reports.
#include <iostream>
#include <memory>

#include "commands.h"
#include "oblique/protocol/shell_text.h"
#include "oblique/raster/raster.h"
#include "oblique/report/accuracy_report.h"
#include "oblique/report/depth_report.h"

namespace oblique::cli {

void setup_report(CLI::App& app, int& exit_code) {
  struct Settings {
    oblique::report::AccuracyOptions accuracy;
    std::string accuracy_out = "report-out";
    std::vector<std::string> impls, impls_float;
    std::shared_ptr<ContractFlags> contract = std::make_shared<ContractFlags>();
    bool quiet = false;
    oblique::report::DepthOptions depth;
    std::string depth_out = "report-out";
    bool depth_rasterize = false;
  };
  auto settings = std::make_shared<Settings>();
  CLI::App* report =
      app.add_subcommand("report", "Measurement reports (CSV, Markdown, PNG charts)");
  report->require_subcommand(1);
  CLI::App* accuracy = report->add_subcommand(
      "accuracy",
      "Error against run time: every method x scalar type x input regime (typical, tiny near "
      "planes, f/n to 1e12, infinite, orthographic, planes near the eye, the far corner and the "
      "standard near plane, huge and tiny scales) against the exact oracle; stiffness sweeps; the "
      "checker's bound against the measured error. Writes accuracy.csv, stiffness.csv, "
      "accuracy.md and (with gnuplot) accuracy.png and stiffness.png.");
  accuracy->add_option("--out", settings->accuracy_out, "Output directory")->capture_default_str();
  accuracy
      ->add_option("--cases", settings->accuracy.cases_per_step,
                   "Cases per regime and stiffness step")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  accuracy->add_option("--seed", settings->accuracy.seed, "Random seed")->capture_default_str();
  accuracy->add_flag("--quiet", settings->quiet, "No progress lines on standard error");
  accuracy->add_option("--impl", settings->impls,
                       "Also an implementation of yours (the protocol of oblique verify, double): "
                       "asked the same cases over the pipe, its error and round trip per request "
                       "beside the core's methods; may be given more than once");
  accuracy->add_option("--impl-float", settings->impls_float,
                       "The same for an implementation that answers in float");
  // What is measured, as verify's contract says it: conventions, the families of the regimes,
  // how an implementation's refusals are judged.
  accuracy->add_option("--contract", settings->contract->file,
                       "A JSON contract file, as verify's: the conventions and families measured "
                       "and the statuses an implementation's refusals are judged by");
  add_contract_flag(accuracy, settings->contract, "--convention", "conventions",
                    "Conventions to measure, a comma list or all (default all)");
  add_contract_flag(accuracy, settings->contract, "--families", "families",
                    "Comma list of projection families: the regimes that build them are measured "
                    "(perspective, infinite, orthographic, general; default all)");
  add_contract_flag(accuracy, settings->contract, "--statuses", "statuses",
                    "How an implementation's refusals are judged (default any_refusal)");
  accuracy->callback([settings, &exit_code] {
    oblique::report::AccuracyOptions& options = settings->accuracy;
    options.out_dir = settings->accuracy_out;
    options.progress = !settings->quiet;
    const Expected<Contract> contract = settings->contract->read();
    if (!contract) {
      std::cerr << "oblique report accuracy: " << contract.error() << "\n";
      exit_code = 2;
      return;
    }
    options.contract = *contract;
    auto add = [&options](const std::string& command, bool float32) {
      options.implementations.push_back({command, float32, protocol::command_name(command)});
    };
    for (const std::string& c : settings->impls) add(c, false);
    for (const std::string& c : settings->impls_float) add(c, true);
    const auto measured = oblique::report::measure_accuracy(options, std::cerr);
    if (!measured.error.empty()) {
      std::cerr << "oblique report accuracy: " << measured.error << "\n";
      exit_code = 2;
      return;
    }
    exit_code = print_paths(oblique::report::write_accuracy_report(measured, options, std::cerr));
    // A report that measured nothing of an implementation is no pass for it.
    for (const std::string& line : oblique::report::unprofiled_implementations(measured)) {
      std::cerr << "oblique report accuracy: " << line << "\n";
      if (exit_code == 0) exit_code = 1;
    }
  });
  CLI::App* depth = report->add_subcommand(
      "depth",
      "Depth precision: the paper's Figure 5 (maximum NDC z along the view axis, Eq. 19, against "
      "the plane's angle and distance), checked against the core's matrices in every convention, "
      "and the bits of a 24-bit fixed-point and a 32-bit float depth buffer still used along view "
      "directions. Writes figure5.csv, depth_bits.csv, depth.md and (with gnuplot) figure5.png.");
  depth->add_option("--out", settings->depth_out, "Output directory")->capture_default_str();
  depth->add_flag("--rasterize", settings->depth_rasterize,
                  "Also measure Figure 5 on llvmpipe (EGL + OpenGL 4.5): each gl matrix draws the "
                  "view axis's point at infinity and its stored depth is read back; adds "
                  "figure5_measured.png and a z_max_measured column. Exit 3 when the rasterizer "
                  "cannot judge");
  depth->add_option("--far", settings->depth.far_distance, "Far distance of the frustum")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  depth->callback([settings, &exit_code] {
    oblique::report::DepthOptions& options = settings->depth;
    options.out_dir = settings->depth_out;
    if (!(options.far_distance > options.near_distance)) {
      std::cerr << "oblique report depth: --far must exceed the near distance "
                << options.near_distance << "\n";
      exit_code = 2;
      return;
    }
    auto measured = oblique::report::measure_depth(options);
    if (settings->depth_rasterize) {
      // Figure 5 on llvmpipe: each matrix draws the axis's point at infinity into a float depth
      // buffer (oblique::raster::Rasterizer::stored_depths()).
      const auto opened =
          oblique::raster::Rasterizer::open({oblique::raster::Device::software, 16});
      std::string error = opened ? "" : opened.error();
      const auto measure =
          [&](const std::vector<Eigen::Matrix4d>& matrices,
              std::string& why) -> std::optional<std::vector<std::optional<double>>> {
        std::vector<std::optional<double>> out;
        const std::vector<Eigen::Vector4d> axis_end = {Eigen::Vector4d(0, 0, -1, 0)};
        for (const Eigen::Matrix4d& m : matrices) {
          const auto depths = (*opened)->stored_depths(m, axis_end, oblique::Convention::gl,
                                                       oblique::DepthBuffer::float32);
          if (!depths) {
            why = depths.error();
            return std::nullopt;
          }
          out.push_back(depths->front());
        }
        return out;
      };
      if (!opened ||
          !oblique::report::add_measured(measured, measure, (*opened)->renderer(), error)) {
        std::cerr << "oblique report depth: --rasterize: inconclusive: " << error << "\n";
        exit_code = 3;
        return;
      }
    }
    exit_code = print_paths(oblique::report::write_depth_report(measured, options, std::cerr));
  });
}

}  // namespace oblique::cli
