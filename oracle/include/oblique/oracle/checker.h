// Judging answers in your own tests, with any test framework:
//
//   #include <oblique/oracle/checker.h>
//
//   const oblique::oracle::Checker<float> checker(m, plane, oblique::Convention::gl);
//   oblique::Answer<float> mine{oblique::Status::ok, my_matrix};
//   const oblique::oracle::Judgement j = checker.judge(mine);
//   if (const oblique::oracle::Finding* f = j.violation())
//     std::printf("%s: %s; %s against %s\n", std::string(check_name(f->check)).c_str(),
//                 relation_text(*f).c_str(), residual_text(*f).c_str(), bound_text(*f).c_str());
//
// The checker (GMP's rationals behind a floating-point filter that settles most questions without
// them) is compiled in oblique::properties for float, double and long double; this header
// declares it and needs neither GMP nor the checker's headers. Link oblique::properties.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "oblique/depth_convention.h"
#include "oblique/oracle/finding.h"
#include "oblique/oracle/vocabulary.h"
#include "oblique/plane.h"
#include "oblique/status.h"
#include "oblique/util/eigen_layout.h"

namespace oblique::oracle {

template <class T>
class FilteredProblem;

inline namespace OBLIQUE_EIGEN_LAYOUT {  // (oblique/util/eigen_layout.h)

/// Everything the checker knows of one input (M, C, convention), and its judgement of answers to
/// it: the status contract first, then the properties Checks selects, then (when asked) row 3's
/// accuracy.
template <class T>
class Checker {
 public:
  Checker(const Matrix4<T>& m, const Vector4<T>& c, Convention convention);
  ~Checker();
  Checker(Checker&&) noexcept;
  Checker& operator=(Checker&&) noexcept;

  /// The input's status in exact arithmetic (ok: it has an answer).
  Status exact_status() const;
  /// The statuses an answer may carry: the exact one, and the refusals rounding allows near a
  /// status boundary.
  std::vector<Status> acceptable_statuses() const;
  /// Why an implementation with `contract` (and, under StatusContract::exact, the `refusals` it
  /// has; empty: all) is not judged on this input, or "" when it is (not_judged() in finding.h).
  std::string not_judged(StatusContract contract, const std::vector<Status>& refusals = {}) const;
  /// The checks that applied to `outcome`, in order; Judgement::violation() is the first that
  /// fails.
  Judgement judge(const Answer<T>& outcome, const Checks& checks = {}) const;

  /// The filtered checker itself (include oblique/oracle/filtered.h to use it).
  const FilteredProblem<T>& problem() const { return *problem_; }

 private:
  std::unique_ptr<FilteredProblem<T>> problem_;
};

}  // namespace OBLIQUE_EIGEN_LAYOUT

}  // namespace oblique::oracle
