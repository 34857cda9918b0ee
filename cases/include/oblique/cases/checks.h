// What is checked of an implementation's answer (an oblique::Answer, result.h): the vocabulary of
// judge() (judge.h) without the checker.
#pragma once

#include <limits>
#include <vector>

#include "oblique/cases/property.h"
#include "oblique/plane.h"
#include "oblique/result.h"
#include "oblique/status.h"

namespace oblique::cases {

/// How an implementation's statuses are judged.
enum class StatusContract {
  /// Every status must be one the input allows (Problem::acceptable_statuses()): the core.
  exact,
  /// An input without an answer may get any refusal (an external implementation need not name
  /// our status); an input with an answer must be answered, or refused only where rounding allows.
  any_refusal,
  /// The implementation reports no statuses (a printed formula): only an ok answer to an input
  /// that allows none fails.
  answers_only,
};

/// What to check.
struct Checks {
  StatusContract statuses = StatusContract::exact;
  /// The properties judged, in Property's order (extracted_planes_match included by default).
  std::vector<Property> properties = {
      Property::near_is_clip_plane,       Property::side_rows_unchanged,
      Property::far_plane_through_corner, Property::no_clipping,
      Property::infinite_edge_parallel,   Property::extracted_planes_match};
  /// Row 3 within Problem::row3_bounds() of the exact answer.
  bool row3_accuracy = false;
  /// Every entry within this many ulps of the correctly rounded answer (an implementation's own
  /// promise: the accurate method's oracle::tolerance::kAccurateUlps); infinity checks nothing.
  double max_ulps = std::numeric_limits<double>::infinity();
  /// Keep going after a violation and list the checks that hold too (`oblique check`'s table);
  /// otherwise the judgement stops at the first violation.
  bool every = false;
};

}  // namespace oblique::cases
