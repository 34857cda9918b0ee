// oblique check's output: the table a person reads and the JSON object a program reads.
#include <nlohmann/json.hpp>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <string_view>

#include "oblique/protocol/numbers.h"
#include "oblique/report/counterexample_report.h"
#include "oblique/scene/check.h"

namespace oblique::scene {

namespace {

std::string number(double x) {
  return protocol::format_number<double>(x);
}

std::string fixed2(double x) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.2f", x);
  return buffer;
}

nlohmann::ordered_json matrix_json(const Matrix4<double>& m) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (int i = 0; i < 16; ++i) out.push_back(m(i / 4, i % 4));
  return out;
}

/// A consumer's verdict in a line: "ok (64 judged, 3 left out)", "FAIL: ...".
std::string consumer_line(const ConsumerResult& c) {
  if (!c.note.empty()) return "- (" + c.note + ")";
  std::string out = c.violation ? "FAIL" : c.judged ? "ok" : "not judged";
  out += " (" + std::to_string(c.judged) + " judged";
  if (c.left_out()) out += ", " + std::to_string(c.left_out()) + " left out";
  if (c.consumer == SceneConsumer::cascades && c.depth_waste > 0)
    out += ", depth waste " + fixed2(c.depth_waste);
  out += ")";
  if (c.violation) out += ": " + oracle::describe(*c.violation);
  return out;
}

nlohmann::ordered_json consumers_json(const std::vector<ConsumerResult>& list) {
  using json = nlohmann::ordered_json;
  json out = json::object();
  for (const ConsumerResult& c : list) {
    out[std::string(scene_consumer_name(c.consumer))] = {
        {"holds", c.holds()},
        {"judged", c.judged},
        {"left_out", c.left_out()},
        {"note", c.note.empty() ? json(nullptr) : json(c.note)},
        {"worst_ratio", c.worst_ratio},
        {"depth_waste",
         c.consumer == SceneConsumer::cascades ? json(c.depth_waste) : json(nullptr)},
        {"violation", c.violation ? json(oracle::describe(*c.violation)) : json(nullptr)},
        {"inputs", c.violation ? json(c.inputs) : json(nullptr)}};
  }
  return out;
}

}  // namespace

std::string to_json(const SceneCheck& check) {
  using json = nlohmann::ordered_json;  // fields in the documented order; non-finite -> null
  json surfaces = json::array();
  for (const SurfaceCheck& s : check.surfaces) {
    json properties = json::object(), residuals = json::object();
    for (const oracle::Finding& p : s.properties) {
      const std::string name(oracle::check_name(p.check));
      properties[name] = p.holds;
      residuals[name] = p.ratio ? json(*p.ratio) : json(nullptr);
    }
    surfaces.push_back({
        {"name", s.name},
        {"kind", std::string(surface_kind_name(s.kind))},
        {"path", s.path},
        {"level", s.level},
        {"action", s.render ? "render" : "skip"},
        {"reason", s.render ? json(nullptr) : json(s.reason)},
        {"status", std::string(status_code(s.status))},
        {"view", matrix_json(s.view)},
        {"projection", s.projection ? matrix_json(*s.projection) : json(nullptr)},
        {"method", s.render ? json(std::string(method_name(s.method))) : json(nullptr)},
        {"properties", properties},
        {"residuals", residuals},
        {"max_depth", s.depth ? json(s.depth->far_depth) : json(nullptr)},
        {"depth_fraction", s.depth ? json(s.depth->fraction) : json(nullptr)},
        {"depth_bits_lost", s.depth ? json(s.depth->bits_lost) : json(nullptr)},
        {"scissor_ndc", s.scissor
                            ? json({s.scissor->x0, s.scissor->y0, s.scissor->x1, s.scissor->y1})
                            : json(nullptr)},
        {"scissor_pixels",
         s.scissor && s.scissor->pixels ? json(*s.scissor->pixels) : json(nullptr)},
        {"covered_pixels",
         s.scissor && s.scissor->covered_pixels ? json(*s.scissor->covered_pixels) : json(nullptr)},
        {"consumers", s.render ? consumers_json(s.consumers) : json(nullptr)},
    });
    if (s.render && !s.impl_consumers.empty())
      surfaces.back()["impl_consumers"] = consumers_json(s.impl_consumers);
    if (s.impl_answer) {
      json findings = json::array();
      for (const oracle::Finding& f : s.impl_findings)
        findings.push_back({{"property", std::string(oracle::check_name(f.check))},
                            {"holds", f.holds},
                            {"relation", oracle::relation_text(f)},
                            {"residual", oracle::residual_text(f)},
                            {"bound", oracle::bound_text(f)}});
      surfaces.back()["impl"] = {
          {"answer", *s.impl_answer},
          {"precision", std::string(protocol::precision_name(check.impl_precision))},
          {"findings", findings}};
    }
  }
  json out = {{"scene", check.scene},
              {"convention", std::string(convention_name(check.convention))},
              {"depth_buffer", depth_buffer_name(check.depth_buffer)},
              {"max_depth", check.max_depth},
              {"truncated", check.truncated},
              {"unlisted_out_of_view", check.unlisted},
              {"surfaces", surfaces},
              {"impl_diagnosis", check.impl_diagnosis.ran
                                     ? json::parse(report::diagnosis_json(check.impl_diagnosis))
                                     : json(nullptr)}};
  // Who answered impl_consumers: the --shader's functions (float, on the GPU path).
  if (!check.impl_shader.empty()) out["impl_shader"] = check.impl_shader;
  return out.dump(-1, ' ', false, json::error_handler_t::replace);
}

namespace {

/// A name as printed in the table: control characters and DEL escaped (\n, \t, \x1b, ...), so a
/// name cannot move the cursor or forge rows.
std::string printable(std::string_view name) {
  std::string out;
  for (const char ch : name) {
    const auto byte = static_cast<unsigned char>(ch);
    if (ch == '\n') {
      out += "\\n";
    } else if (ch == '\t') {
      out += "\\t";
    } else if (ch == '\r') {
      out += "\\r";
    } else if (ch == '\\') {
      out += "\\\\";
    } else if (byte < 0x20 || byte == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", byte);
      out += hex;
    } else {
      out += ch;
    }
  }
  return out;
}

}  // namespace

std::string to_text(const SceneCheck& check) {
  std::ostringstream out;
  out << "scene " << printable(check.scene) << " (" << convention_name(check.convention) << ", "
      << depth_buffer_name(check.depth_buffer) << " depth buffer, max_depth " << check.max_depth
      << ")\n\n";
  // The summary table, then the details of each rendered pass. The name column is as wide as the
  // longest name up to kNameColumn; a longer name has a line of its own above its row.
  constexpr std::size_t kNameColumn = 32;
  std::vector<std::string> names;
  std::size_t width = 7;
  for (const SurfaceCheck& s : check.surfaces) {
    names.push_back(printable(s.name));
    if (names.back().size() <= kNameColumn) width = std::max(width, names.back().size());
  }
  auto cell = [](std::string text, std::size_t w) {
    text.resize(std::max(w, text.size()), ' ');
    return text;
  };
  out << cell("surface", width) << "  kind    action  properties  depth bits lost  reason\n";
  for (std::size_t i = 0; i < check.surfaces.size(); ++i) {
    const SurfaceCheck& s = check.surfaces[i];
    const bool own_line = names[i].size() > width;
    if (own_line) out << names[i] << "\n";
    out << cell(own_line ? "" : names[i], width) << "  "
        << cell(std::string(surface_kind_name(s.kind)), 6) << "  "
        << cell(s.render ? "render" : "skip", 6) << "  "
        << cell(s.render ? (s.properties_hold() ? "pass" : "FAIL") : "-", 10) << "  "
        << cell(s.depth ? fixed2(s.depth->bits_lost) : "-", 15) << "  " << s.reason << "\n";
  }
  for (const SurfaceCheck& s : check.surfaces) {
    if (!s.render) continue;
    out << "\n" << printable(s.name) << " (" << surface_kind_name(s.kind) << "): ";
    out << "render, " << method_name(s.method) << " method, "
        << (s.properties_hold() ? "every property holds" : "A PROPERTY FAILS") << "\n";
    out << "  view:       ";
    for (int i = 0; i < 4; ++i) {
      out << (i ? "              " : "") << "[";
      for (int j = 0; j < 4; ++j) out << (j ? ", " : "") << number(s.view(i, j));
      out << "]\n";
    }
    out << "  projection: ";
    for (int i = 0; i < 4; ++i) {
      out << (i ? "              " : "") << "[";
      for (int j = 0; j < 4; ++j) out << (j ? ", " : "") << number((*s.projection)(i, j));
      out << "]\n";
    }
    for (const oracle::Finding& p : s.properties) {
      out << "  " << (p.holds ? "ok   " : "FAIL ") << oracle::check_name(p.check);
      if (p.ratio && *p.ratio > 0) out << "  (residual / bound " << number(*p.ratio) << ")";
      out << "\n";
    }
    if (s.depth) {
      out << "  depth along the view axis: reaches " << number(s.depth->far_depth) << ", spans "
          << number(s.depth->fraction) << " of the range: " << number(s.depth->bits_lost)
          << " bits of the "
          << (s.depth->buffer == DepthBuffer::fixed24 ? "24-bit fixed-point" : "32-bit float")
          << " buffer lost\n";
    } else {
      out << "  depth along the view axis: the axis does not pass through the kept region\n";
    }
    if (s.scissor) {
      out << "  scissor (NDC): [" << number(s.scissor->x0) << ", " << number(s.scissor->x1)
          << "] x [" << number(s.scissor->y0) << ", " << number(s.scissor->y1) << "]";
      if (s.scissor->pixels) {
        const auto& px = *s.scissor->pixels;
        out << "; pixels x " << px[0] << ", y " << px[1] << ", " << px[2] << " x " << px[3] << " ("
            << static_cast<long long>(px[2]) * px[3] << " pixels), the surface covers "
            << number(std::round(*s.scissor->covered_pixels)) << " pixels";
      }
      out << "\n";
    }
    for (const ConsumerResult& c : s.consumers)
      out << "  consumer " << scene_consumer_name(c.consumer) << ": " << printable(consumer_line(c))
          << "\n";
  }
  bool any_impl = false;
  for (const SurfaceCheck& s : check.surfaces) any_impl = any_impl || s.impl_answer.has_value();
  if (any_impl) {
    out << "\nthe implementation's answers (--impl), judged as oblique verify --precision "
        << protocol::precision_name(check.impl_precision) << " judges:\n";
    for (const SurfaceCheck& s : check.surfaces) {
      if (!s.impl_answer) continue;
      bool holds = true;
      for (const oracle::Finding& f : s.impl_findings) holds = holds && f.holds;
      out << "  " << printable(s.name) << ": " << (holds ? "pass" : "FAIL") << "\n";
      for (const oracle::Finding& f : s.impl_findings) {
        if (f.holds) continue;
        // A status finding is what the input allows against what came; the others a residual
        // against its bound.
        const bool statuses = f.shows == oracle::Shows::statuses;
        out << "    FAIL " << oracle::check_name(f.check) << ": " << oracle::relation_text(f)
            << "\n      " << (statuses ? "got:      " : "residual: ")
            << printable(oracle::residual_text(f)) << "\n      "
            << (statuses ? "expected: " : "bound:    ") << printable(oracle::bound_text(f)) << "\n";
      }
    }
    if (check.impl_diagnosis.ran)
      out << "  " << mistakes::likely_cause_line(check.impl_diagnosis) << "\n";
  }
  bool any_impl_consumers = false;
  for (const SurfaceCheck& s : check.surfaces)
    any_impl_consumers = any_impl_consumers || !s.impl_consumers.empty();
  if (any_impl_consumers) {
    if (check.impl_shader.empty())
      out << "\nthe implementation's consumers (--impl, "
          << protocol::precision_name(check.impl_precision) << "):\n";
    else
      out << "\nthe shader's consumers (--shader " << printable(check.impl_shader)
          << ", float on the GPU path):\n";
    for (const SurfaceCheck& s : check.surfaces) {
      for (const ConsumerResult& c : s.impl_consumers)
        out << "  " << printable(s.name) << ": " << scene_consumer_name(c.consumer) << " "
            << printable(consumer_line(c)) << "\n";
    }
  }
  if (check.unlisted > 0)
    out << "\n"
        << check.unlisted
        << " more surfaces out of view (or with the camera on their wrong side) are not listed\n";
  if (check.truncated)
    out << "\nmore than " << kMaxPasses << " visible passes: the rest were not looked at\n";
  return out.str();
}

}  // namespace oblique::scene
