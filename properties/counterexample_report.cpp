#include "oblique/properties/counterexample_report.h"

#include <nlohmann/json.hpp>

#include "oblique/protocol/protocol.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#ifndef OBLIQUE_COMPILER
#define OBLIQUE_COMPILER "unknown compiler"
#endif
#ifndef OBLIQUE_CXX_FLAGS
#define OBLIQUE_CXX_FLAGS ""
#endif

namespace oblique::properties {

template <class T>
Counterexample make_counterexample(const Matrix4<T>& m, const Vector4<T>& c,
                                   Convention convention) {
  using protocol::format_number;
  using protocol::Notation;
  Counterexample ce;
  ce.scalar = std::string(protocol::scalar_name<T>());
  ce.convention = std::string(convention_name(convention));
  for (int i = 0; i < 16; ++i) {
    ce.projection_decimal.push_back(format_number(m(i / 4, i % 4)));
    ce.projection_hex.push_back(format_number(m(i / 4, i % 4), Notation::hex));
  }
  for (int i = 0; i < 4; ++i) {
    ce.plane_decimal.push_back(format_number(c(i)));
    ce.plane_hex.push_back(format_number(c(i), Notation::hex));
  }
  ce.request = protocol::request_line(m, c, convention, Notation::hex);
  ce.request_decimal = protocol::request_line(m, c, convention, Notation::shortest);
  return ce;
}

template <class T>
void set_result(Counterexample& ce, const Matrix4<T>& result) {
  ce.result_decimal.clear();
  for (int i = 0; i < 16; ++i)
    ce.result_decimal.push_back(protocol::format_number(result(i / 4, i % 4)));
}

#define OBLIQUE_COUNTEREXAMPLE(T)                                                      \
  template Counterexample make_counterexample<T>(const Matrix4<T>&, const Vector4<T>&, \
                                                 Convention);                          \
  template void set_result<T>(Counterexample&, const Matrix4<T>&);
OBLIQUE_COUNTEREXAMPLE(float)
OBLIQUE_COUNTEREXAMPLE(double)
OBLIQUE_COUNTEREXAMPLE(long double)
#undef OBLIQUE_COUNTEREXAMPLE

namespace {

std::string matrix_table(const std::vector<std::string>& values) {
  std::ostringstream out;
  out << "| | col 1 | col 2 | col 3 | col 4 |\n|---|---|---|---|---|\n";
  for (int i = 0; i < 4; ++i) {
    out << "| row " << i + 1 << " |";
    for (int j = 0; j < 4; ++j) out << " `" << values[static_cast<std::size_t>(4 * i + j)] << "` |";
    out << "\n";
  }
  return out.str();
}

std::string core_method_of(const std::string& implementation) {
  const std::string prefix = "core_";
  if (implementation.rfind(prefix, 0) != 0) return "";
  const std::string method = implementation.substr(prefix.size());
  return method;
}

/// Writes `text` to a temporary file beside `path`, then renames it into place.
void write_file(const std::string& path, const std::string& text) {
  const std::string temporary = path + ".partial";
  {
    std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
    file << text;
    file.flush();
    if (!file) {
      std::filesystem::remove(temporary);
      throw std::runtime_error("cannot write " + temporary);
    }
  }
  std::filesystem::rename(temporary, path);
}

}  // namespace

std::string write_report(const Counterexample& ce, const ReportContext& context) {
  std::filesystem::create_directories(context.directory);
  std::string stem =
      context.stem.empty() ? context.test_id + "." + ce.implementation : context.stem;
  for (char& ch : stem) {
    if (ch == '/' || ch == ' ') ch = '_';
  }
  if (context.keep_existing) {
    const std::string base = stem;
    for (int n = 2; std::filesystem::exists(context.directory + "/" + stem + ".md") ||
                    std::filesystem::exists(context.directory + "/" + stem + ".json");
         ++n)
      stem = base + "-" + std::to_string(n);
  }
  const std::string md_path = context.directory + "/" + stem + ".md";
  const std::string json_path = context.directory + "/" + stem + ".json";
  const std::string rc_params = "RC_PARAMS=\"seed=" + std::to_string(context.seed) +
                                " max_success=" + std::to_string(context.max_success) + "\"";
  const std::string impl_env =
      ce.implementation.rfind("core_", 0) == 0 ? "" : "OBLIQUE_IMPL=" + ce.implementation + " ";
  const std::string replay_suite = !context.replay_run.empty()
                                       ? context.replay_run
                                       : impl_env + rc_params + " " + context.binary +
                                             " --gtest_filter='" + context.test_id + "'";
  const std::string method = core_method_of(ce.implementation);
  const std::string replay_case = !context.replay_case.empty() ? context.replay_case
                                  : method.empty()             ? ""
                                                   : "echo '" + ce.request + "' | " + context.cli +
                                                         " apply --method " + method +
                                                         " --precision " + ce.scalar;

  std::ostringstream md;
  const Finding& f = ce.finding;
  md << "# Counterexample: " << f.kind << " (" << ce.implementation << ", " << ce.scalar << ")\n\n";
  md << "**Relation:** " << f.relation << "\n\n";
  if (!f.expected.empty()) {  // a status finding: what was expected and what came
    md << "| | status |\n|---|---|\n| expected | `" << f.expected << "` |\n| got | `" << f.got
       << "` |\n";
  } else {
    md << "| side | value |\n|---|---|\n| residual | `" << f.lhs << "` |\n| bound | `" << f.rhs
       << "` |\n| residual / bound | `" << protocol::format_number(f.ratio) << "` |\n";
  }
  md << "\nFamily `" << ce.family << "`, convention `" << ce.convention << "`, place `" << ce.place
     << "`.\n\n## Input\n\nProjection M (shortest round-trip decimals):\n\n"
     << matrix_table(ce.projection_decimal) << "\nProjection M (hex, exact):\n\n"
     << matrix_table(ce.projection_hex) << "\nPlane C: `(" << ce.plane_decimal[0] << ", "
     << ce.plane_decimal[1] << ", " << ce.plane_decimal[2] << ", " << ce.plane_decimal[3]
     << ")` = `(" << ce.plane_hex[0] << ", " << ce.plane_hex[1] << ", " << ce.plane_hex[2] << ", "
     << ce.plane_hex[3] << ")`\n\n";
  if (!ce.result_decimal.empty())
    md << "## Result M'\n\n" << matrix_table(ce.result_decimal) << "\n";
  if (!ce.notes.empty()) {
    md << "## Notes\n\n| | |\n|---|---|\n";
    for (const auto& [key, value] : ce.notes) {
      std::string cell = value;
      for (char& ch : cell) {
        if (ch == '\n' || ch == '|') ch = ch == '|' ? '/' : ' ';
      }
      md << "| " << key << " | `" << cell << "` |\n";
    }
    md << "\n";
  }
  md << "## Replay\n\nThe whole run, shrinking included (seed " << context.seed << "):\n\n```sh\n"
     << replay_suite << "\n```\n\n";
  if (!replay_case.empty()) md << "This one case alone:\n\n```sh\n" << replay_case << "\n```\n\n";
  md << "Built with " << OBLIQUE_COMPILER << ", flags `" << OBLIQUE_CXX_FLAGS << "`.\n";

  nlohmann::json j;
  j["property"] = f.kind;
  j["relation"] = f.relation;
  j["lhs"] = f.lhs;
  j["rhs"] = f.rhs;
  j["ratio"] = f.ratio;
  j["implementation"] = ce.implementation;
  j["precision"] = ce.scalar;
  j["family"] = ce.family;
  j["convention"] = ce.convention;
  j["place"] = ce.place;
  j["projection"] = ce.projection_hex;
  j["plane"] = ce.plane_hex;
  j["projection_decimal"] = ce.projection_decimal;
  j["plane_decimal"] = ce.plane_decimal;
  j["result"] = ce.result_decimal;
  j["status_expected"] = f.expected;
  j["status_answered"] = f.got;
  j["seed"] = context.seed;
  j["replay"] = replay_suite;
  j["replay_case"] = replay_case;
  j["request"] = ce.request;
  j["request_decimal"] = ce.request_decimal;
  nlohmann::json notes = nlohmann::json::object();
  for (const auto& [key, value] : ce.notes) notes[key] = value;
  j["notes"] = notes;
  j["compiler"] = OBLIQUE_COMPILER;
  j["flags"] = OBLIQUE_CXX_FLAGS;
  // Text from other programs may be any bytes: invalid UTF-8 becomes U+FFFD, never an abort.
  write_file(json_path, j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
  write_file(md_path, md.str());
  return md_path;
}

}  // namespace oblique::properties
