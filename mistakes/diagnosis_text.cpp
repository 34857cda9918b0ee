// The words of a diagnosis (diagnosis.h): cause names, the console line and the report's
// "Likely cause" section.
#include <algorithm>
#include <cstdio>
#include <sstream>

#include "oblique/mistakes/diagnosis.h"
#include "oblique/protocol/numbers.h"

namespace oblique::mistakes {

std::string cause_name(const std::vector<Mistake>& cause) {
  std::string out;
  for (Mistake m : cause) out += (out.empty() ? "" : " + ") + std::string(mistake_entry(m).name);
  return out;
}

namespace {

/// "wrong_face" or "wrong_face or camera_space_signs"; "no known mistake" for none.
std::string causes_text(const std::vector<std::vector<Mistake>>& causes) {
  if (causes.empty()) return "no known mistake";
  std::string out;
  for (const auto& cause : causes) out += (out.empty() ? "" : " or ") + cause_name(cause);
  return out;
}

/// What an answer does, in a phrase: "C's multiple 0.5 times the right one, the far plane misses
/// Q".
std::string geometry_phrase(const AnswerGeometry& g) {
  if (!g.side_rows_kept)
    return "row " + std::to_string(g.changed_row) + " changed (only row 3 may change)";
  std::ostringstream out;
  out.precision(4);
  if (!g.in_span)
    out << "row 3 is no multiple of C plus one of M_4";
  else
    out << "C's multiple " << g.alpha_ratio << " times the right one"
        << (g.beta_right ? "" : ", M_4's off");
  if (g.near_wrong_side) out << ", the wrong side of C kept";
  if (!g.far_through_q) out << ", the far plane misses Q";
  if (g.clips) out << ", the view volume clipped";
  return out.str();
}

/// "right on perspective, off_axis; on y_flipped: wrong_face": each family's own diagnosis, and
/// where none explains a family's answers, what they show.
std::string by_family_text(const std::vector<FamilyDiagnosis>& families) {
  std::string right, wrong;
  for (const FamilyDiagnosis& f : families) {
    const std::string name(cases::family_name(f.family));
    if (f.wrong == 0) {
      right += (right.empty() ? "" : ", ") + name;
    } else {
      wrong += "; on " + name + ": " + causes_text(f.causes);
      if (f.causes.empty() && f.geometry) wrong += " (" + geometry_phrase(*f.geometry) + ")";
    }
  }
  return "right on " + right + wrong;
}

/// "row 3 off by 3.1% (19 of 24 bits lost)" or "row 3 not finite".
std::string lost_text(const NumericalCause& n) {
  if (n.non_finite) return "a step divides by 0 and row 3 is not finite";
  std::ostringstream out;
  char error[32];
  std::snprintf(error, sizeof error, "%.3g%%", 100 * n.relative_error);
  out << "a step loses " << n.bits_lost << " of " << n.precision
      << " bits: C's multiple a C in row 3 off by " << error;
  return out.str();
}

/// "you take ... (shows on ...); you ..." for each mistake of a cause.
std::string you_text(const std::vector<Mistake>& cause) {
  std::string out;
  for (Mistake m : cause) {
    const MistakeEntry& e = mistake_entry(m);
    out +=
        (out.empty() ? "" : "; ") + std::string(e.you) + " (wrong on " + std::string(e.shows) + ")";
  }
  return out;
}

}  // namespace

namespace {

constexpr const char* kTransposedLayout =
    "the matrix read transposed: every answer is the right modification of M^T, transposed back, "
    "or changes M's third column where the modification changes its third row (a row-vector "
    "engine, v M as DirectXMath and D3DX multiply, declared as column vectors; or its 16 numbers "
    "read in the other order)";
constexpr const char* kTransposedLayoutFix =
    "declare how the function stores its matrix: oblique::Layout::row_vectors for a row-vector "
    "engine (adapt()), or the other of row_major and column_major";

}  // namespace

std::string cause_names(const Diagnosis& d) {
  if (!d.ran) return "";
  if (d.transposed_layout) return "transposed_layout";
  if (d.numerical)
    return "numerical: " + std::string(numerical_route_entry(d.numerical->route).name);
  if (d.causes.empty() && !d.families.empty()) return by_family_text(d.families);
  return causes_text(d.causes);
}

std::string likely_cause_line(const Diagnosis& d) {
  if (!d.ran) return "";
  if (d.transposed_layout)
    return std::string("likely cause: transposed_layout (") + kTransposedLayout +
           "); fix: " + kTransposedLayoutFix;
  if (d.numerical) {
    const NumericalRouteEntry& e = numerical_route_entry(d.numerical->route);
    return "likely cause: numerical: " + std::string(e.name) + " (" + std::string(e.title) +
           "): the right formula, but " + lost_text(*d.numerical) +
           "; rewrite: " + std::string(e.rewrite);
  }
  if (d.causes.empty() && !d.families.empty())
    return "likely cause, by family (no one known mistake reproduces every answer): " +
           by_family_text(d.families);
  if (d.causes.empty()) return "likely cause: no known mistake reproduces these answers";
  std::string out = "likely cause: ";
  for (std::size_t i = 0; i < d.causes.size(); ++i) {
    out += (i ? " or " : "") + cause_name(d.causes[i]);
    if (d.causes[i].size() == 1)
      out += " (" + std::string(mistake_entry(d.causes[i][0]).title) + ")";
  }
  if (d.causes.size() == 1 && d.causes[0].size() == 1)
    out += "; fix: " + std::string(mistake_entry(d.causes[0][0]).fix);
  if (d.causes.size() == 1 && d.causes[0].size() > 1) out += ": " + you_text(d.causes[0]);
  return out;
}

std::string choice_text(const ChoiceDifference& c) {
  auto number = [](double v) { return protocol::format_number(v); };
  auto yes = [](double v) { return v != 0 ? std::string("yes") : std::string("no"); };
  auto convention = [](double v) {
    return std::string(convention_name(static_cast<Convention>(static_cast<int>(v))));
  };
  switch (c.choice) {
    case Choice::camera_guard:
      return "refuses for C_w >= 0: " + yes(c.mistaken) + " (right: " + yes(c.right) + ")";
    case Choice::head_on: return "M returned unchanged: " + yes(c.mistaken) + " (right: no)";
    case Choice::solve: return "entries of M left out of the solves: " + yes(c.mistaken);
    case Choice::closed_form: return "Q by the perspective closed form: " + yes(c.mistaken);
    case Choice::nan_sign: return "a corner sign computed as NaN (x / |x| at 0)";
    case Choice::corner_guard:
      return "refuses for C . Q <= 0: " + yes(c.mistaken) + " (right: " + yes(c.right) + ")";
    case Choice::sign_x:
      return "the far corner's x sign: " + number(c.mistaken) + " (right: " + number(c.right) + ")";
    case Choice::sign_y:
      return "the far corner's y sign: " + number(c.mistaken) + " (right: " + number(c.right) + ")";
    case Choice::face:
      return "the far corner's depth Q'_z: " + number(c.mistaken) + " (right: " + number(c.right) +
             ")";
    case Choice::formula:
      return "the formula of " + convention(c.mistaken) + " (right: " + convention(c.right) + ")";
    case Choice::row4: return "row 4 rewritten: " + yes(c.mistaken);
    case Choice::factor:
      return "the factor a = " + number(c.mistaken) + " / (C . Q) (right: " + number(c.right) +
             " / (C . Q))";
    case Choice::form:
      return "row 3's multiple of M_4: " + number(c.mistaken) + " (right: " + number(c.right) + ")";
    case Choice::q_z: return "the closed form's Q_z taken as -1: " + yes(c.mistaken);
    case Choice::q_w: return "the closed form's Q_w of a left-handed matrix: " + yes(c.mistaken);
    case Choice::m4:
      return "row 3's M_4 taken as the perspective shape's (0, 0, -1, 0): " + yes(c.mistaken);
    case Choice::route:
      return "the formula run in another convention's range, the row brought back: " +
             yes(c.mistaken);
  }
  return "";
}

std::string likely_cause_markdown(const Diagnosis& d) {
  if (!d.ran) return "";
  std::ostringstream md;
  md << "## Likely cause\n\n";
  if (d.transposed_layout) {
    md << "**`transposed_layout`: " << kTransposedLayout << ".** No formula mistake reproduces "
       << "these answers (" << d.seen << " cases judged, " << d.wrong << " answers wrong); each "
       << "is what a function that reads its matrix transposed returns: the correct modification "
       << "of M^T transposed back, or M with its third column rewritten.\n\n"
       << "Fix: " << kTransposedLayoutFix << ".\n\n";
    return md.str();
  }
  if (d.numerical) {
    const NumericalRouteEntry& e = numerical_route_entry(d.numerical->route);
    md << "**A numerical cause, `" << e.name << "`: " << e.title << ".** No formula mistake "
       << "reproduces these answers (" << d.seen << " cases judged, " << d.wrong
       << " answers wrong); the correct formula along this route, every step rounded in the "
       << "program's precision, reproduces each.\n\n"
       << e.step << "\n\n"
       << "Measured on the first wrong answer: " << lost_text(*d.numerical) << ".\n\n"
       << "Rewrite: " << e.rewrite << "\n\n"
       << "It shows on " << e.shows << ".\n\n";
    return md.str();
  }
  if (d.causes.empty()) {
    md << "No known mistake reproduces these answers (" << d.seen << " cases judged, " << d.wrong
       << " answers wrong; catalogue: docs/mistakes.md).\n\n";
    if (!d.families.empty()) {
      md << "They part by family: right on some, wrong on others. Each family alone:\n\n"
         << "| family | what sets it apart | cases | wrong | likely cause |\n"
         << "|---|---|---|---|---|\n";
      for (const FamilyDiagnosis& f : d.families) {
        std::string cause = f.wrong == 0 ? std::string("right") : "`" + causes_text(f.causes) + "`";
        if (f.wrong > 0 && f.causes.empty() && f.geometry)
          cause += ": " + geometry_phrase(*f.geometry);
        md << "| " << cases::family_name(f.family) << " | " << cases::family_shape(f.family)
           << " | " << f.seen << " | " << f.wrong << " | " << cause << " |\n";
      }
      md << "\nThe code takes another path on the families where it is wrong; the condition that "
            "sends it there is in what sets them apart.\n\n";
      for (const FamilyDiagnosis& f : d.families) {
        if (f.causes.size() != 1) continue;
        for (Mistake m : f.causes.front()) {
          const MistakeEntry& e = mistake_entry(m);
          md << "**On " << cases::family_name(f.family) << ": `" << e.name << "`: " << e.title
             << ".** " << e.explanation << "\n\nFix: " << e.fix << "\n\n";
        }
      }
    }
    if (d.geometry) md << answer_geometry_markdown(*d.geometry);
    return md.str();
  }
  if (d.causes.size() > 1) {
    md << "Each of these reproduces every answer seen; the cases asked do not tell them apart:\n\n";
    for (const auto& cause : d.causes) md << "- `" << cause_name(cause) << "`\n";
    md << "\nThe first, in detail:\n\n";
  }
  if (d.causes.front().size() > 1) {
    md << "The smallest set of known mistakes that reproduces every answer has "
       << d.causes.front().size() << ", made together:\n\n";
    for (Mistake m : d.causes.front()) {
      const MistakeEntry& e = mistake_entry(m);
      md << "- " << e.you << " (wrong on " << e.shows << ")\n";
    }
    md << "\n";
  }
  for (Mistake m : d.causes.front()) {
    const MistakeEntry& e = mistake_entry(m);
    md << "**`" << e.name << "`: " << e.title << ".** " << e.explanation << "\n\n"
       << "Fix: " << e.fix << "\n\n"
       << "It shows on " << e.shows << ".\n\n";
  }
  md << "Evidence: of " << d.seen << " cases judged (" << d.probed
     << " of them asked to tell the causes apart), " << d.decided
     << " have an answer this cause decides; it reproduces each answer. Where its answer is not "
        "the correct one, the implementation's answer was wrong ("
     << d.wrong_where_it_differs << " cases); where it is, the answer was right ("
     << d.right_where_it_agrees << " cases).\n\n";
  if (!d.differences.empty()) {
    md << "On the first such case it decides otherwise than the correct method:\n\n";
    for (const ChoiceDifference& c : d.differences) md << "- " << choice_text(c) << "\n";
    md << "\n";
  }
  auto row = [](const std::optional<std::array<double, 4>>& r, Status s) {
    if (s != Status::ok) return std::string(status_code(s));
    if (!r) return std::string("(not decided)");
    std::string out = "(";
    for (int i = 0; i < 4; ++i) out += (i ? ", " : "") + protocol::format_number((*r)[i]);
    return out + ")";
  };
  md << "| row " << d.row + 1 << " of M' | |\n|---|---|\n"
     << "| answered | " << row(d.answered_row, d.answered) << " |\n"
     << "| with this mistake (exact, rounded) | " << row(d.mistaken_row, d.mistaken) << " |\n"
     << "| correct (exact, rounded) | " << row(d.right_row, d.right) << " |\n\n";
  return md.str();
}

}  // namespace oblique::mistakes
