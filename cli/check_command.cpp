// `oblique check`: a scene file, its passes, --impl, --plot and --rasterize.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <iterator>
#include <memory>
#include <optional>
#include <sstream>
#include <vector>

#include "commands.h"
#include "oblique/cases/contract.h"
#include "oblique/protocol/matrix_order.h"
#include "oblique/protocol/names.h"
#include "oblique/protocol/protocol.h"
#include "oblique/raster/raster.h"
#include "oblique/report/html_page.h"
#include "oblique/report/report_files.h"
#include "oblique/run/tally.h"
#include "oblique/scene/check.h"
#include "oblique/scene/plot.h"
#include "oblique/shader/shader_runner.h"

namespace oblique::cli {

struct CheckSettings {
  std::string scene_path;
  bool as_json = false;
  std::string precision = "double";  ///< --precision: of the requests --impl gets, and its bounds
  std::string impl;    ///< --impl CMD: the user's implementation, over the apply protocol
  std::string shader;  ///< --shader FILE[:FUNCTION]: the reconstruction consumer's shader
  std::optional<oblique::shader::Language> shader_language;
  std::vector<std::string> shader_defines;
  std::optional<oblique::shader::VDirection> shader_v;                         ///< --uv-v
  oblique::shader::Vectors shader_vectors = oblique::shader::Vectors::column;  ///< --vectors
  oblique::oracle::Sampling sampling = oblique::oracle::Sampling::pixels;      ///< --sampling
  std::string plot_dir;                                                        ///< --plot DIR
  std::string html;                                                            ///< --html FILE
  double timeout_seconds = 10;
  bool rasterize = false;           ///< --rasterize
  std::string device = "software";  ///< --device
  int raster_size = 1000;           ///< --raster-size
  bool strict = false;              ///< --strict
  /// --consumers LIST: of the scene's consumers, those asked and judged ("none": none).
  std::optional<std::string> consumers;
  std::string layout = "row_major";  ///< --layout: the --impl program's matrix storage
};

/// The exit status of a raster check that could not judge (no EGL, a self-check tripped).
constexpr int kInconclusive = 3;

std::string with_commas(long n) {
  std::string digits = std::to_string(n), out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

/// One rendered pass on the rasterizer: our matrix, or the --impl program's answer (for M and C
/// as its request had them).
struct RasterPass {
  std::string name;
  raster::Result result;
};

/// --rasterize: every rendered pass's matrix drawn and judged (oblique::raster). Writes the
/// table's lines (or a JSON member) and returns 0, 1 (a pass fails) or kInconclusive.
int rasterize(const CheckSettings& settings, const scene::Scene& scene,
              const scene::SceneCheck& check, std::string& text, std::string& json) {
  raster::Options options;
  options.device = settings.device == "gpu" ? raster::Device::gpu : raster::Device::software;
  options.size = settings.raster_size;
  const auto opened = raster::Rasterizer::open(options);
  if (!opened) {
    text = "raster: inconclusive: " + opened.error() + "\n";
    json = "\"raster\": {\"outcome\": \"inconclusive\", \"why\": " +
           protocol::json_string(opened.error()) + "}";
    return kInconclusive;
  }
  raster::Rasterizer& rasterizer = **opened;
  const std::string buffer(depth_buffer_name(check.depth_buffer));
  text = "raster: " + rasterizer.renderer() + "; " + std::to_string(options.size) + " x " +
         std::to_string(options.size) + " samples a pass, " + buffer + " depth\n";
  json = "\"raster\": {\"renderer\": " + protocol::json_string(rasterizer.renderer()) +
         ", \"size\": " + std::to_string(options.size) + ", \"passes\": [";
  int status = 0;
  bool first = true;
  const bool float_requests = check.impl_precision == protocol::Precision::float32;
  for (const scene::SurfaceCheck& pass : check.surfaces) {
    if (!pass.render || !pass.projection) continue;
    Eigen::Matrix4d m = pass.camera_projection;
    Eigen::Vector4d c = pass.plane_in_camera;
    Eigen::Matrix4d answer = *pass.projection;
    std::string refused;
    if (pass.impl_answer) {
      // As the request had them: rounded to float for --precision float.
      if (float_requests) {
        m = m.cast<float>().cast<double>();
        c = c.cast<float>().cast<double>();
      }
      const auto read = protocol::read_answer<double>(*pass.impl_answer);
      if (!read || read->status != Status::ok)
        refused = "the implementation gave no matrix for this pass";
      else
        answer = read->projection;
    }
    raster::Result r;
    if (!refused.empty()) {
      r.why = refused;
    } else {
      // The answer's precision: the --impl program's (--precision), else ours (double).
      int bits = 53;
      if (pass.impl_answer && check.impl_precision == protocol::Precision::float32) bits = 24;
      if (pass.impl_answer && check.impl_precision == protocol::Precision::long_double) bits = 64;
      r = rasterizer.check(m, c, answer, scene.convention, check.depth_buffer, 1, bits);
    }
    char line[512];
    if (r.outcome == raster::Outcome::pass) {
      std::snprintf(line, sizeof line,
                    "raster: %s: pass (%s placed, %s drawn, %s within a band; depth across the "
                    "kept region in [%.9g, %.9g]: 2^%.2f buffer values, %s seen; %.2f s)\n",
                    pass.name.c_str(), with_commas(r.placed).c_str(), with_commas(r.drawn).c_str(),
                    with_commas(r.undecidable).c_str(), r.depth.low, r.depth.high, r.depth.bits,
                    with_commas(r.depth.observed).c_str(), r.render_seconds + r.judge_seconds);
    } else {
      std::snprintf(line, sizeof line, "raster: %s: %s %s\n", pass.name.c_str(),
                    r.outcome == raster::Outcome::fail ? "FAIL" : "inconclusive:", r.why.c_str());
    }
    text += line;
    // The depth buffer along the view axis, measured, beside check's analytic figure.
    std::optional<raster::AxisDepth> axis;
    if (r.rendered) {
      if (const auto measured =
              rasterizer.axis_depth(m, c, answer, scene.convention, check.depth_buffer)) {
        axis = *measured;
        std::snprintf(line, sizeof line,
                      "  depth along the view axis, measured: stored in [%.9g, %.9g], %s values "
                      "of %s samples: %.4f bits lost",
                      axis->low, axis->high, with_commas(static_cast<long>(axis->values)).c_str(),
                      with_commas(axis->drawn).c_str(), axis->bits_lost);
        text += line;
        if (pass.depth) {
          std::snprintf(line, sizeof line, " (analytic %.4f)", pass.depth->bits_lost);
          text += line;
        }
        text += "\n";
      }
    }
    for (const raster::Flag& f : r.examples) {
      std::snprintf(line, sizeof line,
                    "  %s: sample %ld at (%.9g, %.9g, %.9g), C . v = %.17g, band %.3g\n",
                    std::string(raster::flag_name(f.kind)).c_str(), f.sample, f.point.x(),
                    f.point.y(), f.point.z(), f.c_dot, f.band);
      text += line;
    }
    json += std::string(first ? "" : ", ") + "{\"name\": " + protocol::json_string(pass.name) +
            ", \"outcome\": \"" + std::string(raster::outcome_name(r.outcome)) +
            "\", \"why\": " + protocol::json_string(r.why) +
            ", \"placed\": " + std::to_string(r.placed) +
            ", \"drawn\": " + std::to_string(r.drawn) +
            ", \"drawn_behind_c\": " + std::to_string(r.drawn_behind_c) +
            ", \"clipped_kept\": " + std::to_string(r.clipped_kept) +
            ", \"wrong_pixel\": " + std::to_string(r.wrong_pixel) +
            ", \"depth_bits\": " + protocol::json_number(r.depth.bits) + ", \"axis_bits_lost\": " +
            (axis ? protocol::json_number(axis->bits_lost) : std::string("null")) + "}";
    first = false;
    if (r.outcome == raster::Outcome::fail) status = 1;
    if (r.outcome == raster::Outcome::inconclusive && status == 0) status = kInconclusive;
  }
  json += "]}";
  return status;
}

int run_check(const CheckSettings& settings) {
  const std::string& path = settings.scene_path;
  const oblique::scene::ParsedScene parsed = oblique::scene::read_scene_file(path);
  if (!parsed.scene) {
    std::cerr << "oblique check: " << path << ": " << parsed.error << "\n";
    return 2;
  }
  for (const std::string& warning : parsed.warnings)
    std::cerr << "oblique check: " << path << ": warning: " << warning << "\n";
  oblique::scene::Scene scene = *parsed.scene;
  if (settings.consumers) {
    // --consumers: the scene's consumers narrowed (a program that answers the matrix alone, a
    // shader that answers reconstruction alone, on a scene that names more).
    std::vector<oblique::scene::SceneConsumer> kept;
    for (const std::string& name : split_list(*settings.consumers)) {
      if (name == "none") continue;
      const auto consumer = oblique::scene::parse_scene_consumer(name);
      if (!consumer) {
        std::cerr << "oblique check: --consumers: "
                  << oblique::protocol::unknown_name(
                         "scene consumer", name,
                         oblique::names_in(oblique::scene::scene_consumer_names))
                  << ", or none\n";
        return 2;
      }
      if (std::find(scene.consumers.begin(), scene.consumers.end(), *consumer) ==
          scene.consumers.end()) {
        std::cerr << "oblique check: --consumers: " << path << " names no consumer " << name
                  << "\n";
        return 2;
      }
      if (std::find(kept.begin(), kept.end(), *consumer) == kept.end()) kept.push_back(*consumer);
    }
    scene.consumers = kept;
  }
  oblique::scene::SceneCheck check = oblique::scene::check_scene(scene);
  check.impl_precision = *oblique::protocol::parse_precision(settings.precision);
  check.impl_order = *oblique::protocol::matrix_order_of_layout(settings.layout);
  if (!settings.shader.empty() && !settings.impl.empty()) {
    std::cerr << "oblique check: --shader and --impl each name what answers: give one\n";
    return 2;
  }
  // --shader: the scene's reconstruction consumer answered by the shader on the GPU path; the
  // pass's coverage is then the shader's, of that consumer.
  std::unique_ptr<oblique::shader::ShaderRunner> runner;
  if (!settings.shader.empty()) {
    const auto [file, function] = oblique::shader::split_shader_spec(settings.shader);
    oblique::Expected<std::vector<oblique::shader::ShaderFunction>> functions =
        std::vector<oblique::shader::ShaderFunction>{};
    if (!function.empty()) {
      const auto f = oblique::shader::shader_function_in(
          file, function, settings.shader_language, settings.shader_defines,
          settings.timeout_seconds, settings.shader_v, settings.shader_vectors);
      if (f)
        functions->push_back(*f);
      else
        functions =
            oblique::Expected<std::vector<oblique::shader::ShaderFunction>>::failure(f.error());
    } else {
      functions = oblique::shader::shader_functions(settings.shader,
                                                    {oblique::protocol::ConsumerKind::view_position,
                                                     oblique::protocol::ConsumerKind::linear_depth},
                                                    settings.shader_language);
    }
    if (!functions) {
      std::cerr << "oblique check: --shader " << settings.shader << ": " << functions.error()
                << "\n";
      return 2;
    }
    for (oblique::shader::ShaderFunction& f : *functions) {
      f.defines = settings.shader_defines;
      if (settings.shader_v) f.v = *settings.shader_v;
      f.vectors = settings.shader_vectors;
    }
    oblique::shader::RunnerOptions options;
    options.device =
        settings.device == "gpu" ? oblique::raster::Device::gpu : oblique::raster::Device::software;
    options.timeout_seconds = settings.timeout_seconds;
    auto opened = oblique::shader::ShaderRunner::open(*functions, options);
    if (!opened) {
      std::cerr << "oblique check: " << opened.error() << "\n";
      return 2;
    }
    runner = std::move(*opened);
    const oblique::Expected<oblique::Done> judged = oblique::scene::judge_shader_consumers(
        scene, check,
        oblique::shader::shader_consumers(*runner, settings.shader, settings.sampling));
    if (!judged) {
      std::cerr << "oblique check: " << judged.error() << "\n";
      return 2;
    }
  }
  if (!settings.impl.empty()) {
    const oblique::Expected<std::size_t> judged =
        oblique::scene::judge_implementation(scene, check, settings.impl, settings.timeout_seconds);
    if (!judged) {
      std::cerr << "oblique check: " << judged.error() << "\n";
      return 2;
    }
    const oblique::Expected<oblique::Done> consumers =
        oblique::scene::judge_implementation_consumers(scene, check, settings.impl,
                                                       settings.timeout_seconds, settings.sampling);
    if (!consumers) {
      std::cerr << "oblique check: " << consumers.error() << "\n";
      return 2;
    }
  }
  std::string raster_text, raster_json;
  const int raster_status =
      settings.rasterize ? rasterize(settings, scene, check, raster_text, raster_json) : 0;
  if (settings.as_json) {
    std::string json = oblique::scene::to_json(check);
    if (settings.rasterize && !json.empty() && json.back() == '}')
      json.insert(json.size() - 1, ", " + raster_json);
    std::cout << json << "\n";
  } else {
    std::cout << oblique::scene::to_text(check) << raster_text;
  }
  const std::string page_text = oblique::scene::to_text(check) + raster_text;
  if (!settings.html.empty()) {
    // One file, whole or not at all (written beside its place, then renamed).
    const std::filesystem::path page = settings.html;
    // The page replaces a file of that name, never anything else (a device, a folder).
    std::error_code ec;
    const std::string name = page.filename().string();
    if (name.empty() || name == "." || name == "..") {
      std::cerr << "oblique check: cannot write the page " << settings.html
                << ": it names a folder, not a file (give the page's file name, such as "
                << (page.parent_path().empty() ? std::string("scene.html")
                                               : (page.parent_path() / "scene.html").string())
                << "); nothing written\n";
      return 2;
    }
    if (std::filesystem::exists(page, ec) && !std::filesystem::is_regular_file(page, ec)) {
      std::cerr << "oblique check: cannot write the page " << settings.html
                << ": it names something other than a file; nothing written\n";
      return 2;
    }
    oblique::report::ReportFiles files(page.parent_path().empty() ? "." : page.parent_path());
    files.open(page.filename().string()) << oblique::report::views_html(
        oblique::scene::scene_views(scene, check).views, page_text, {});
    std::ostringstream log;
    if (!files.commit(log)) {
      std::cerr << "oblique check: cannot write the page " << settings.html << ": " << log.str();
      return 2;
    }
    (settings.as_json ? std::cerr : std::cout) << "page: " << settings.html << "\n";
  }
  if (!settings.plot_dir.empty()) {
    const oblique::scene::PlotResult plot =
        oblique::scene::write_plot(scene, check, settings.plot_dir, page_text);
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
    for (const auto& file : plot.written)
      if (file.extension() == ".html") paths << "page: " << file.string() << " (in 3D)\n";
  }
  // A pass means judged: a consumer the scene names with nothing judged is no pass; one mostly
  // left out is said (and fails under --strict).
  const oblique::scene::ConsumerCoverage coverage = oblique::scene::consumer_coverage(
      settings.shader.empty() ? scene : oblique::scene::reconstruction_only(scene), check,
      !settings.impl.empty() || !settings.shader.empty());
  if (!coverage.partly.empty())
    (settings.as_json ? std::cerr : std::cout)
        << oblique::run::partly_judged_warning(coverage.partly, settings.strict);
  if (!check.passes() || raster_status == 1) return 1;
  if (!coverage.unjudged.empty() || (settings.strict && !coverage.partly.empty())) {
    for (const std::string& line : coverage.unjudged)
      std::cerr << "oblique check: " << line << "\n";
    std::cerr << (coverage.unjudged.empty()
                      ? "oblique check: --strict: a consumer the scene names was judged in part "
                        "only; not a pass\n"
                      : "oblique check: not all the consumers the scene names were judged; not a "
                        "pass\n");
    return 2;
  }
  return raster_status;
}

void setup_check(CLI::App& app, int& exit_code) {
  auto settings = std::make_shared<CheckSettings>();
  CLI::App* check = app.add_subcommand(
      "check",
      "Check the mirrors, portals and clip planes of a scene file: for each pass (recursively up "
      "to the scene's max_depth), render or skip (with the reason), the pass camera's view and "
      "oblique projection, the properties that apply, the depth precision left and the scissor "
      "rectangle. Exit 0: every rendered pass passes; 1: a property fails (ours, or the "
      "implementation's with --impl, or on the rasterizer); 2: the scene cannot be read, the "
      "implementation does not answer, or the output or picture cannot be written, or a "
      "consumer the scene names had nothing judged (with --strict: more than 10% left out); 3: "
      "--rasterize could not judge (inconclusive).");
  check->add_option("SCENE", settings->scene_path, "The scene file (JSON; see the README)")
      ->required();
  check->add_flag("--json", settings->as_json, "Print one JSON object instead of a table");
  check->add_option("--impl", settings->impl,
                    "Send each rendered pass's request to this command (run by /bin/sh, speaking "
                    "the apply protocol) and judge its answers as oblique verify does; the scene's "
                    "consumers are asked of it too, in their request kinds");
  check
      ->add_option("--layout", settings->layout,
                   "With --impl: how it takes and writes its matrices: row_major (M by rows, the "
                   "protocol's order; the default), column_major or row_vectors (a row-vector "
                   "engine's R = M^T by rows, the same numbers), as oblique verify --layout")
      ->check(CLI::IsMember(std::vector<std::string>(std::begin(oblique::protocol::kLayoutNames),
                                                     std::end(oblique::protocol::kLayoutNames))));
  add_precision_option(
      check, settings->precision,
      "With --impl: the scalar type the implementation computes in; its requests "
      "are rounded to it and its answers judged with its bounds (as oblique "
      "verify --precision)",
      {std::begin(oblique::protocol::all_precisions), std::end(oblique::protocol::all_precisions)});
  check->add_option(
      "--shader", settings->shader,
      "Answer the scene's reconstruction consumer with a GLSL or HLSL file's depth functions on "
      "the GPU path (FILE: functions named view_position and linear_depth; FILE:FUNCTION: one), "
      "judged on every rendered pass (docs/shaders.md)");
  check
      ->add_option_function<std::string>(
          "--shader-language",
          [settings](const std::string& name) {
            settings->shader_language = oblique::shader::parse_language(name);
          },
          "glsl or hlsl (default: by the file's extension)")
      ->check(CLI::IsMember({"glsl", "hlsl"}));
  add_uv_v_option(check, settings->shader_v);
  add_vectors_option(check, settings->shader_vectors);
  add_sampling_option(check, settings->sampling);
  check->add_option("-D,--define", settings->shader_defines,
                    "With --shader: a define of the engine's, NAME or NAME=VALUE (repeat it): the "
                    "shader's #if variants are chosen under them and OBLIQUE_CONVENTION");
  check
      ->add_option("--timeout", settings->timeout_seconds,
                   "With --impl: seconds to wait for each answer (with --shader: for each "
                   "dispatch)")
      ->check(CLI::PositiveNumber);
  check->add_option("--plot", settings->plot_dir,
                    "Write a top and a side view (gnuplot PNG) of the scene and its passes here, "
                    "and scene.html (the scene in 3D)");
  check->add_option("--html", settings->html,
                    "Write the scene as one self-contained HTML page: the camera, every rendered "
                    "pass and its volume in 3D to turn, layers to show or hide, the check beside");
  check->add_flag("--rasterize", settings->rasterize,
                  "Also draw each rendered pass's matrix (ours, or the --impl program's) on a real "
                  "rasterizer, one sample a pixel, and judge what it clipped and stored: nothing "
                  "behind C drawn, nothing of the original volume on C's kept side clipped "
                  "(beyond float32's bands). Exit 3 when the rasterizer cannot judge "
                  "(inconclusive: no EGL, a self-check tripped)");
  check
      ->add_option("--device", settings->device,
                   "With --rasterize or --shader: software (Mesa's llvmpipe, the default) or gpu "
                   "(the machine's driver; its renderer is printed)")
      ->check(CLI::IsMember({"software", "gpu"}));
  check
      ->add_option("--raster-size", settings->raster_size,
                   "With --rasterize: the frame is N x N pixels, one sample each")
      ->check(CLI::Range(16, 4096));
  check->add_option_function<std::string>(
      "--consumers", [settings](const std::string& list) { settings->consumers = list; },
      "Of the consumers the scene names, ask and judge these only (a comma list, or none): a "
      "program that answers the matrix alone (--impl), or a shader that answers "
      "reconstruction, on a scene that names more");
  check->add_flag("--strict", settings->strict,
                  "A consumer the scene names with more than 10% of its answers left out fails "
                  "the check (exit 2) instead of a warning");
  check->callback([settings, &exit_code] { exit_code = run_check(*settings); });
}

}  // namespace oblique::cli
