// `oblique check`: a scene file, its passes, --impl and --plot.
#include <iostream>
#include <memory>

#include "commands.h"
#include "oblique/scene/check.h"
#include "oblique/scene/plot.h"

namespace oblique::cli {

struct CheckSettings {
  std::string scene_path;
  bool as_json = false;
  std::string precision = "double";  ///< --precision: of the requests --impl gets, and its bounds
  std::string impl;      ///< --impl CMD: the user's implementation, over the apply protocol
  std::string plot_dir;  ///< --plot DIR
  double timeout_seconds = 10;
};

int run_check(const CheckSettings& settings) {
  const std::string& path = settings.scene_path;
  const oblique::scene::ParsedScene parsed = oblique::scene::read_scene_file(path);
  if (!parsed.scene) {
    std::cerr << "oblique check: " << path << ": " << parsed.error << "\n";
    return 2;
  }
  oblique::scene::SceneCheck check = oblique::scene::check_scene(*parsed.scene);
  check.impl_precision = *oblique::protocol::parse_precision(settings.precision);
  if (!settings.impl.empty()) {
    const oblique::Expected<std::size_t> judged = oblique::scene::judge_implementation(
        *parsed.scene, check, settings.impl, settings.timeout_seconds);
    if (!judged) {
      std::cerr << "oblique check: " << judged.error() << "\n";
      return 2;
    }
    const oblique::Expected<oblique::Done> consumers =
        oblique::scene::judge_implementation_consumers(*parsed.scene, check, settings.impl,
                                                       settings.timeout_seconds);
    if (!consumers) {
      std::cerr << "oblique check: " << consumers.error() << "\n";
      return 2;
    }
  }
  std::cout << (settings.as_json ? oblique::scene::to_json(check) + "\n"
                                 : oblique::scene::to_text(check));
  if (!settings.plot_dir.empty()) {
    const oblique::scene::PlotResult plot =
        oblique::scene::write_plot(*parsed.scene, check, settings.plot_dir);
    if (!plot.error.empty()) {
      std::cerr << "oblique check: cannot write the picture to " << settings.plot_dir << ": "
                << plot.error << "\n";
      return 2;
    }
    // With --json, standard output stays one JSON object: the paths go to standard error.
    std::ostream& paths = settings.as_json ? std::cerr : std::cout;
    if (!settings.as_json) paths << "\n";
    // The view across the first mirror or portal first: it shows the pass.
    if (!plot.across.empty())
      paths << "picture: " << plot.across.string() << " (across " << plot.across_surface << ")\n";
    for (const auto& file : plot.written) {
      if (file.extension() == ".png" && file != plot.across)
        paths << "picture: " << file.string() << "\n";
    }
  }
  return check.passes() ? 0 : 1;
}

void setup_check(CLI::App& app, int& exit_code) {
  auto settings = std::make_shared<CheckSettings>();
  CLI::App* check = app.add_subcommand(
      "check",
      "Check the mirrors, portals and clip planes of a scene file: for each pass (recursively up "
      "to the scene's max_depth), render or skip (with the reason), the pass camera's view and "
      "oblique projection, the properties that apply, the depth precision left and the scissor "
      "rectangle. Exit 0: every rendered pass passes; 1: a property fails (ours, or the "
      "implementation's with --impl); 2: the scene cannot be read, the implementation does not "
      "answer, or the output or picture cannot be written.");
  check->add_option("SCENE", settings->scene_path, "The scene file (JSON; see the README)")
      ->required();
  check->add_flag("--json", settings->as_json, "Print one JSON object instead of a table");
  check->add_option("--impl", settings->impl,
                    "Send each rendered pass's request to this command (run by /bin/sh, speaking "
                    "the apply protocol) and judge its answers as oblique verify does; the scene's "
                    "consumers are asked of it too, in their request kinds");
  add_precision_option(
      check, settings->precision,
      "With --impl: the scalar type the implementation computes in; its requests "
      "are rounded to it and its answers judged with its bounds (as oblique "
      "verify --precision)",
      {std::begin(oblique::protocol::all_precisions), std::end(oblique::protocol::all_precisions)});
  check
      ->add_option("--timeout", settings->timeout_seconds,
                   "With --impl: seconds to wait for each answer")
      ->check(CLI::PositiveNumber);
  check->add_option("--plot", settings->plot_dir,
                    "Write a top and a side view (gnuplot PNG) of the scene and its passes here");
  check->callback([settings, &exit_code] { exit_code = run_check(*settings); });
}

}  // namespace oblique::cli
