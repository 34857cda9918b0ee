// The words of a finding: what its check compares and what it measured, made from its numbers
// when a report or a console line is written (finding.h).
#include "oblique/oracle/finding.h"

#include <string>

#include "oblique/protocol/numbers.h"

namespace oblique::oracle {
namespace {

using protocol::format_number;

std::string entry_name(const Finding& f) {
  return "(" + std::to_string(f.row) + "," + std::to_string(f.column) + ")";
}

}  // namespace

std::string_view check_name(Check c) noexcept {
  if (const std::optional<Property> p = property_of(c)) return property_name(*p);
  return name_in(tool_check_names, c);
}

std::optional<Check> parse_check(std::string_view name) noexcept {
  if (const std::optional<Property> p = cases::parse_property(name)) return check_of(*p);
  return value_in(tool_check_names, name);
}

std::string relation_text(const Finding& f) {
  if (f.shows == Shows::non_finite_answer && property_of(f.check)) return "M' is finite";
  switch (f.check) {
    case Check::status:
      return f.answered != Status::ok && f.exact == Status::ok
                 ? "an input with an answer is answered (or refused only where rounding allows)"
             : f.answered != Status::ok ? "an input without an answer is refused with its status"
             : f.exact == Status::ok    ? "an answer beyond the range of the type is refused"
                                        : "an input without an answer is refused";
    case Check::finite_result: return "an ok answer is finite";
    case Check::near_is_clip_plane:
      return "some lambda > 0 has |near'_i - lambda C_i| <= gamma(3) (lambda |C_i| + |M4_i|) "
             "for every i (or, where that fails, within u lambda max|C_j| more: a change no "
             "rasterizer sees)";
    case Check::side_rows_unchanged:
      return "rows 1, 2, 4 of M' are those of M (equal values; -0 equals +0)";
    case Check::far_plane_through_corner:
      return f.shows == Shows::no_bound
                 ? "not judged: C is within rounding of Q (gamma(16) kappa >= 1)"
                 : "|far' . Q| <= bound";
    case Check::no_clipping:
      return "far' . p >= -bound at every vertex p of the view volume with C . p >= 0";
    case Check::infinite_edge_parallel:
      return "Q_w = 0 and |far' . Q| <= bound (far' parallel to the frustum edge Q)";
    case Check::extracted_planes_match:
      return "frustum_planes(M') has the side planes of M and a near plane n with n . C > 0";
    case Check::row3_accuracy:
      return "|M'_3i - exact M'_3i| <= bound_i (what careful arithmetic in the answer's type "
             "achieves)";
    case Check::accurate_ulps:
      return "every entry of M' within " + format_number(f.bound) +
             " ulp of the correctly rounded exact answer";
    case Check::methods_agree: return "|M'_3i(closed form) - M'_3i(general)| <= 2 bound_i";
    case Check::crash: return "the implementation answers every request and keeps running";
    case Check::timeout: return "an answer within " + format_number(f.bound) + " s (--timeout)";
    case Check::protocol: return "the answer is a protocol answer line";
  }
  return "";
}

std::string residual_text(const Finding& f) {
  switch (f.shows) {
    case Shows::residual:
      if (f.check == Check::accurate_ulps) return format_number(f.residual) + " ulp";
      if (f.check == Check::methods_agree)
        return "entry " + std::to_string(f.column) + ": " + format_number(f.residual);
      return format_number(f.residual);
    case Shows::certified:
      return f.check == Check::accurate_ulps ? format_number(f.residual) + " ulp (certified)"
                                             : "certified";
    case Shows::statuses: return std::string(status_code(f.answered));
    case Shows::non_finite_answer: return "M' has a NaN or infinite entry";
    case Shows::lambda_fit:
    case Shows::wrong_side:
    case Shows::no_fit:
      return "lambda = " + format_number(f.lambda) +
             (f.shows == Shows::wrong_side ? " (wrong side: near' is C negated)" : "") +
             ", worst residual/bound = " + format_number(f.residual) +
             (f.shows == Shows::lambda_fit ? "" : ", no lambda > 0 fits every entry");
    case Shows::entry:
      if (f.check == Check::row3_accuracy)
        return "entry " + std::to_string(f.column) + ": |" + format_number(f.value) + " - " +
               format_number(f.reference) + "| = " + format_number(f.residual);
      return "M'" + entry_name(f) + " = " + format_number(f.value);
    case Shows::below_at_corner: return "far' . p = " + format_number(f.residual) + " at a corner";
    case Shows::below_at_edge_crossing:
      return "far' . p = " + format_number(f.residual) + " at an edge crossing of C";
    case Shows::no_vertex_below: return "no vertex below its bound";
    case Shows::side_plane_differs:
      return "side plane " + std::to_string(f.row) + " differs by " + format_number(f.residual);
    case Shows::near_plane_not_finite: return "the near plane has a NaN or infinite component";
    case Shows::near_plane_side: return "n . C = " + format_number(f.residual);
    case Shows::no_bound: return "C lies within rounding of the far corner";
    case Shows::edge_direction:
      return "Q_w = " + format_number(f.reference) + ", far' . Q = " + format_number(f.residual);
    case Shows::program: return f.message;
  }
  return "";
}

std::string bound_text(const Finding& f) {
  switch (f.shows) {
    case Shows::residual:
    case Shows::edge_direction:
      return format_number(f.bound) + (f.check == Check::accurate_ulps ? " ulp" : "");
    case Shows::certified:
      return f.check == Check::accurate_ulps ? format_number(f.bound) + " ulp" : "";
    case Shows::statuses: return status_list(f.allowed);
    case Shows::non_finite_answer:
    case Shows::near_plane_not_finite: return "finite";
    case Shows::lambda_fit:
    case Shows::wrong_side:
    case Shows::no_fit: return "1";
    case Shows::entry:
      if (f.check == Check::row3_accuracy) return format_number(f.bound);
      return "M" + entry_name(f) + " = " + format_number(f.reference);
    case Shows::below_at_corner:
    case Shows::below_at_edge_crossing: return "-" + format_number(f.bound);
    case Shows::no_vertex_below:
    case Shows::side_plane_differs: return "0";
    case Shows::near_plane_side: return "> 0";
    case Shows::no_bound: return "no bound";
    case Shows::program:
      return f.check == Check::protocol ? "{\"status\": ..., \"projection\": [16 numbers]}"
                                        : "an answer line";
  }
  return "";
}

std::string sides_text(const Finding& f, const std::string& indent) {
  const bool statuses = f.shows == Shows::statuses;
  return indent + (statuses ? "expected: " : "residual: ") +
         (statuses ? bound_text(f) : residual_text(f)) + "\n" + indent +
         (statuses ? "got:      " : "bound:    ") + (statuses ? residual_text(f) : bound_text(f)) +
         "\n";
}

std::vector<std::pair<std::string, double>> finding_numbers(const Finding& f) {
  using Numbers = std::vector<std::pair<std::string, double>>;
  switch (f.shows) {
    case Shows::residual:
    case Shows::below_at_corner:
    case Shows::below_at_edge_crossing:
      return Numbers{{"residual", f.residual}, {"bound", f.bound}};
    case Shows::lambda_fit:
    case Shows::wrong_side:
    case Shows::no_fit:
      return Numbers{{"lambda", f.lambda}, {"residual", f.residual}, {"bound", f.bound}};
    case Shows::entry: {
      Numbers out{
          {"row", f.row}, {"column", f.column}, {"value", f.value}, {"reference", f.reference}};
      if (f.check == Check::row3_accuracy) {
        out.emplace_back("residual", f.residual);
        out.emplace_back("bound", f.bound);
      }
      return out;
    }
    case Shows::side_plane_differs: return Numbers{{"row", f.row}, {"residual", f.residual}};
    case Shows::near_plane_side: return Numbers{{"residual", f.residual}};
    case Shows::edge_direction:
      return Numbers{{"reference", f.reference}, {"residual", f.residual}, {"bound", f.bound}};
    case Shows::certified:
      if (f.check == Check::accurate_ulps)
        return Numbers{{"residual", f.residual}, {"bound", f.bound}};
      return {};
    default: return {};
  }
}

}  // namespace oblique::oracle
