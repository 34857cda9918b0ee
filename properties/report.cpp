#include "report.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#ifndef OBLIQUE_COMPILER
#define OBLIQUE_COMPILER "unknown compiler"
#endif
#ifndef OBLIQUE_CXX_FLAGS
#define OBLIQUE_CXX_FLAGS ""
#endif

namespace oblique::properties {

namespace {

template <class V>
std::string printed(const char* format, V x) {
  char b[64];
  std::snprintf(b, sizeof b, format, x);
  return b;
}

}  // namespace

// Round-trip decimal digits (max_digits10) and exact hex for each scalar type.
template <>
std::string decimal<float>(float x) {
  return printed("%.9g", static_cast<double>(x));
}
template <>
std::string decimal<double>(double x) {
  return printed("%.17g", x);
}
template <>
std::string decimal<long double>(long double x) {
  return printed("%.21Lg", x);
}
template <>
std::string hexadecimal<float>(float x) {
  return printed("%a", static_cast<double>(x));
}
template <>
std::string hexadecimal<double>(double x) {
  return printed("%a", x);
}
template <>
std::string hexadecimal<long double>(long double x) {
  return printed("%La", x);
}
template <>
const char* scalar_name<float>() {
  return "float";
}
template <>
const char* scalar_name<double>() {
  return "double";
}
template <>
const char* scalar_name<long double>() {
  return "long_double";
}

template <class T>
Counterexample make_counterexample(const Matrix4<T>& m, const Vector4<T>& c) {
  Counterexample ce;
  ce.scalar = scalar_name<T>();
  for (int i = 0; i < 16; ++i) {
    ce.projection_decimal.push_back(decimal(m(i / 4, i % 4)));
    ce.projection_hex.push_back(hexadecimal(m(i / 4, i % 4)));
  }
  for (int i = 0; i < 4; ++i) {
    ce.plane_decimal.push_back(decimal(c(i)));
    ce.plane_hex.push_back(hexadecimal(c(i)));
  }
  return ce;
}
template Counterexample make_counterexample<float>(const Matrix4<float>&, const Vector4<float>&);
template Counterexample make_counterexample<double>(const Matrix4<double>&, const Vector4<double>&);
template Counterexample make_counterexample<long double>(const Matrix4<long double>&,
                                                         const Vector4<long double>&);

namespace {

std::string json_number(const std::string& hex) {
  // Non-finite values are protocol strings; finite ones are exact hex-float strings.
  if (hex == "nan" || hex == "-nan") return "\"nan\"";
  if (hex == "inf") return "\"inf\"";
  if (hex == "-inf") return "\"-inf\"";
  return "\"" + hex + "\"";
}

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

}  // namespace

namespace {

/// A request line from number texts, each passed through `number` on the way.
template <class Number>
std::string request_from(const std::vector<std::string>& projection,
                         const std::vector<std::string>& plane, const std::string& convention,
                         Number number) {
  std::string line = "{\"projection\": [";
  for (std::size_t i = 0; i < projection.size(); ++i)
    line += (i ? ", " : "") + number(projection[i]);
  line += "], \"plane\": [";
  for (std::size_t i = 0; i < plane.size(); ++i) line += (i ? ", " : "") + number(plane[i]);
  line += "], \"convention\": \"" + convention + "\"}";
  return line;
}

}  // namespace

std::string request_line(const Counterexample& ce) {
  return request_from(ce.projection_hex, ce.plane_hex, ce.convention, json_number);
}

std::string request_line_decimal(const Counterexample& ce) {
  return request_from(
      ce.projection_decimal, ce.plane_decimal, ce.convention, [](const std::string& text) {
        const bool non_finite = text == "nan" || text == "-nan" || text == "inf" || text == "-inf";
        return non_finite ? json_number(text) : text;
      });
}

std::string write_report(const Counterexample& ce, const ReportContext& context) {
  std::filesystem::create_directories(context.directory);
  std::string stem =
      context.stem.empty() ? context.test_id + "." + ce.implementation : context.stem;
  for (char& ch : stem) {
    if (ch == '/' || ch == ' ') ch = '_';
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
                                                   : "echo '" + request_line(ce) + "' | " +
                                                         context.cli + " apply --method " + method +
                                                         " --precision " + ce.scalar;

  std::ofstream md(md_path);
  md << "# Counterexample: " << ce.property << " (" << ce.implementation << ", " << ce.scalar
     << ")\n\n";
  md << "**Relation:** " << ce.relation << "\n\n";
  md << "| side | value |\n|---|---|\n| residual | `" << ce.lhs << "` |\n| bound | `" << ce.rhs
     << "` |\n| residual / bound | `" << decimal(ce.ratio) << "` |\n";
  if (!ce.status_expected.empty()) {
    md << "| status expected | `" << ce.status_expected << "` |\n| status answered | `"
       << ce.status_got << "` |\n";
  }
  md << "\nFamily `" << ce.family << "`, convention `" << ce.convention << "`, place `" << ce.place
     << "`.\n\n## Input\n\nProjection M (%.17g):\n\n"
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
  j["property"] = ce.property;
  j["relation"] = ce.relation;
  j["lhs"] = ce.lhs;
  j["rhs"] = ce.rhs;
  j["ratio"] = ce.ratio;
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
  j["status_expected"] = ce.status_expected;
  j["status_answered"] = ce.status_got;
  j["seed"] = context.seed;
  j["replay"] = replay_suite;
  j["replay_case"] = replay_case;
  j["request"] = request_line(ce);
  j["request_decimal"] = request_line_decimal(ce);
  nlohmann::json notes = nlohmann::json::object();
  for (const auto& [key, value] : ce.notes) notes[key] = value;
  j["notes"] = notes;
  j["compiler"] = OBLIQUE_COMPILER;
  j["flags"] = OBLIQUE_CXX_FLAGS;
  std::ofstream(json_path) << j.dump(2) << "\n";
  return md_path;
}

}  // namespace oblique::properties
