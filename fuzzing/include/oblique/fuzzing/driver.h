// The fuzz driver's parts (oblique/fuzzing.h is its front): the input decoder (scalar type,
// convention, method, a projection of a family built from decoded parameters or 16 raw numbers,
// and a plane), the case's judge (one filtered checker per case, one judgement per distinct
// answer) and check(), which runs an implementation on a case and aborts on a violation. The
// project's own fuzz target (fuzz/fuzz_oblique.cpp) uses them directly, to judge several
// implementations per case; fuzzing/fuzzing.cpp builds test_one_input() from them.
//
// Special values: libFuzzer's comparison tracing does not see double compares, so 0, -0,
// subnormals, DBL_MIN, DBL_MAX, powers of two and ties are picked by index.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "oblique/cases/case_builder.h"
#include "oblique/cases/contract.h"
#include "oblique/fuzzing.h"
#include "oblique/mistakes/implementations.h"
#include "oblique/oblique.h"
#include "oblique/oracle/adapter.h"
#include "oblique/oracle/filtered.h"
#include "oblique/oracle/judge.h"
#include "oblique/projection.h"
#include "oblique/protocol/numbers.h"
#include "oblique/run/tally.h"

namespace oblique::fuzzing {

/// Reads bytes front to back; past the end it yields zeros.
class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  std::uint8_t byte() { return pos_ < size_ ? data_[pos_++] : 0; }
  /// The next 8 bytes as a double's bits, the first the lowest (as x86 stores one). Assembled
  /// in an integer: a byte array filled in a loop drew GCC 12's -Wstringop-overflow false alarm.
  double raw_double() {
    std::uint64_t bits = 0;
    for (int i = 0; i < 8; ++i) bits |= std::uint64_t{byte()} << (8 * i);
    double d;
    std::memcpy(&d, &bits, sizeof d);
    return d;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

/// The special values, by index. A selector byte below kSpecialCount picks one; 255 reads 8 raw
/// bytes; anything else gives a small dyadic (selector - kSpecialCount - 64) / 8.
inline double special_value(int index) {
  constexpr double dmax = std::numeric_limits<double>::max();
  constexpr double dmin = std::numeric_limits<double>::min();
  constexpr double denorm = std::numeric_limits<double>::denorm_min();
  constexpr double eps = std::numeric_limits<double>::epsilon();
  const double table[] = {0.0,
                          -0.0,
                          1.0,
                          -1.0,
                          2.0,
                          0.5,
                          -2.0,
                          -0.5,
                          dmin,
                          -dmin,
                          denorm,
                          -denorm,
                          dmax,
                          -dmax,
                          eps,
                          1.0 + eps,
                          1.0 - eps / 2,
                          1e-6,
                          1e12,
                          1e-12,
                          1e6,
                          0.1,
                          3.0,
                          0.25,
                          -0.25,
                          1e-300,
                          1e300,
                          std::ldexp(1.0, -1074 + 52),
                          0.75,
                          1.5,
                          4.0,
                          -4.0,
                          1.0 / 3,
                          std::ldexp(1.0, 1023),
                          std::numeric_limits<double>::infinity(),
                          -std::numeric_limits<double>::infinity(),
                          std::numeric_limits<double>::quiet_NaN()};
  constexpr int count = sizeof(table) / sizeof(table[0]);
  return table[index % count];
}
constexpr int kSpecialCount = 37;

inline double number(ByteReader& in) {
  const int selector = in.byte();
  if (selector < kSpecialCount) return special_value(selector);
  if (selector == 255) return in.raw_double();
  return (selector - kSpecialCount - 64) / 8.0;
}

/// A decoded fuzz input: the scalar type and method it is run in, and the case, in long double
/// (which holds each scalar type's numbers exactly).
struct FuzzCase {
  protocol::Precision scalar = protocol::Precision::float64;
  Method method = Method::automatic;
  /// How the numbers were made. kBuilt: by the case builder (case_builder.h) from the bytes as
  /// its picks, in the scalar type; `input` says the family, place and defect. Else decoded from
  /// the bytes as numbers (special values, raw doubles), the shapes the hunt for extreme inputs
  /// uses: 0..4 built (frustum, infinite, orthographic, y-flipped frustum, rotated), 5 raw, 6 a
  /// frustum or infinite frustum times a camera shift T(tx, ty, 0): M14, M24 != 0 (stereo, lens
  /// shift; cases::Family::stereo_shift), 7 an x-flipped frustum (M11 < 0, a mirror camera;
  /// cases::Family::x_flipped), 8 an x- and y-flipped one (cases::Family::xy_flipped),
  /// 9 a left-handed frustum or infinite frustum (camera z negated, M43 = +1;
  /// cases::Family::left_handed).
  int family = 0;
  cases::Case<long double> input;
};
inline constexpr int kBuilt = 10;

/// What the case is, in words: a decoded shape ("frustum", "raw", ...), or a built case's
/// family, place and defect ("built off_axis at near_eye", "built perspective at typical, spoiled:
/// singular").
inline std::string family_label(const FuzzCase& c) {
  if (c.family == kBuilt) {
    std::string out = "built " + std::string(cases::family_name(c.input.family)) + " at " +
                      std::string(cases::place_name(c.input.place));
    if (c.input.defect) out += ", spoiled: " + std::string(cases::defect_name(*c.input.defect));
    return out;
  }
  const char* names[] = {"frustum", "infinite",     "orthographic", "y_flipped",  "rotated",
                         "raw",     "stereo_shift", "x_flipped",    "xy_flipped", "left_handed"};
  return names[c.family % 10];
}

/// The generator families (oblique/cases/case_kinds.h) a decoded case is one of, for a
/// contract's families: a built frustum is perspective when centred (M13 = M23 = 0), else
/// off_axis or jittered (the decoder does not tell them apart); raw numbers are general.
inline std::vector<cases::Family> contract_families(const FuzzCase& c) {
  using cases::Family;
  const Matrix4<long double>& m = c.input.matrix;
  switch (c.family) {
    case kBuilt: return {c.input.family};
    case 0:
      if (m(0, 2) == 0 && m(1, 2) == 0) return {Family::perspective};
      return {Family::off_axis, Family::jittered};
    case 1: return {Family::infinite};
    case 2: return {Family::orthographic};
    case 3: return {Family::y_flipped};
    case 4: return {Family::rotated};
    case 6: return {Family::stereo_shift};
    case 7: return {Family::x_flipped};
    case 8: return {Family::xy_flipped};
    case 9: return {Family::left_handed};
    default: return {Family::general};
  }
}

inline constexpr std::uint8_t kShiftMarker = 0x53;       // 'S'
inline constexpr std::uint8_t kFlipXMarker = 0x58;       // 'X'
inline constexpr std::uint8_t kLeftHandedMarker = 0x4c;  // 'L'

/// The family byte (the fourth) in [kBuiltLow, kBuiltHigh) makes a built case (FuzzCase::kBuilt).
/// A window where no kept input's family byte lies (fuzz/regressions, fuzz/corpus when it came
/// in), so each of them decodes as it did when it was kept; libFuzzer's comparison tracing finds
/// it.
inline constexpr int kBuiltLow = 192, kBuiltHigh = 208;

/// Every family, convention, place and defect: the contract of the project's own fuzz target.
inline const Contract& every_case() {
  static const Contract every =
      resolved(Contract{}, cases::every_convention(), cases::StatusContract::exact, false);
  return every;
}

/// The numbers of a decoded shape (FuzzCase::family 0 .. 9) into m and plane; `c.family` is the
/// family byte's shape on entry. Builder parameters that break a builder's preconditions fall
/// back to raw.
inline void decode_numbers(ByteReader& in, FuzzCase& c, Convention convention, Matrix4<double>& m,
                           Vector4<double>& plane) {
  if (c.family == 5) {
    for (int i = 0; i < 16; ++i) m(i / 4, i % 4) = number(in);
  } else {
    const double l = number(in), r = number(in), b = number(in), t = number(in);
    const double n = number(in), f = number(in);
    const bool finite = std::isfinite(l) && std::isfinite(r) && std::isfinite(b) &&
                        std::isfinite(t) && std::isfinite(n) && std::isfinite(f);
    const bool sides = finite && l != r && b != t;
    if (c.family == 2 && sides && n != f) {
      m = orthographic(l, r, b, t, n, f, convention);
    } else if (c.family == 1 && sides && n > 0) {
      m = infinite_frustum(l, r, b, t, n, convention);
    } else if (sides && n > 0 && f > n) {
      m = frustum(l, r, b, t, n, f, convention);
      if (c.family == 3) m.row(1) *= -1;
      if (c.family == 4) {
        const double angle = number(in);
        const double ca = std::cos(angle), sa = std::sin(angle);
        Matrix4<double> rot = Matrix4<double>::Identity();
        rot(0, 0) = ca, rot(0, 2) = sa, rot(2, 0) = -sa, rot(2, 2) = ca;
        if (std::isfinite(ca) && std::isfinite(sa)) m = m * rot;
      }
    } else {
      c.family = 5;
      for (int i = 0; i < 16; ++i) m(i / 4, i % 4) = number(in);
    }
  }
  for (int i = 0; i < 4; ++i) plane(i) = number(in);
  // After the plane, the byte kShiftMarker shifts a frustum or infinite frustum by (tx, ty, 0)
  // (two more numbers); kFlipXMarker negates row 1 of a frustum or y-flipped frustum (M11 < 0);
  // kLeftHandedMarker negates column 3 of a frustum or infinite frustum (camera z, M43 = +1).
  // Inputs that end earlier, or go on with another byte, decode as before (the family byte
  // keeps its meaning: new families come behind markers, not from a larger modulus).
  const bool shiftable = c.family == 0 || c.family == 1, flippable = c.family == 0 || c.family == 3;
  const int marker = shiftable || flippable ? in.byte() : -1;
  if (flippable && marker == kFlipXMarker) {
    m.row(0) *= -1;
    c.family = c.family == 0 ? 7 : 8;
  } else if (shiftable && marker == kShiftMarker) {
    Matrix4<double> shift = Matrix4<double>::Identity();
    shift(0, 3) = number(in);
    shift(1, 3) = number(in);
    if (std::isfinite(shift(0, 3)) && std::isfinite(shift(1, 3))) {
      m = m * shift;
      c.family = 6;
    }
  } else if (shiftable && marker == kLeftHandedMarker) {
    m.col(2) = Vector4<double>::Zero() - m.col(2);
    c.family = 9;
  }
}

template <class T>
cases::Case<long double> widened(const cases::Case<T>& c) {
  cases::Case<long double> out;
  out.family = c.family;
  out.convention = c.convention;
  out.place = c.place;
  out.defect = c.defect;
  out.matrix = c.matrix.template cast<long double>();
  out.plane = c.plane.template cast<long double>();
  return out;
}

/// Decodes a fuzz input. Byte 0 picks the scalar type, byte 2 the method. The family byte (byte
/// 3) in [kBuiltLow, kBuiltHigh): the rest of the input is the case builder's picks (choose_case():
/// one byte a pick, two for a pick of more than 256 values), so the case is one of `contract`'s
/// families, conventions and places, as a property run draws them, built in the scalar type and
/// spoiled by one of its defects one time in five when `defects`. Otherwise it picks a
/// shape (its value modulo 6; decode_numbers()), byte 1 one of the contract's conventions, and
/// the rest are numbers: special values and raw doubles, the hunt for extreme inputs.
/// `contract` is resolved (oblique::resolved(): no list empty).
inline FuzzCase decode(const std::uint8_t* data, std::size_t size,
                       const Contract& contract = every_case(), bool defects = true) {
  ByteReader in(data, size);
  FuzzCase c;
  c.scalar = protocol::all_precisions[in.byte() % 3];
  const int convention_byte = in.byte();
  c.method = all_methods[in.byte() % std::size(all_methods)];
  const int family_byte = in.byte();
  if (family_byte >= kBuiltLow && family_byte < kBuiltHigh) {
    c.family = kBuilt;
    const cases::Pick pick = [&in](int lo, int hi) {
      const auto n = static_cast<unsigned>(hi - lo);
      unsigned v = in.byte();
      if (n > 256) v |= unsigned{in.byte()} << 8;
      return lo + static_cast<int>(v % n);
    };
    switch (c.scalar) {
      case protocol::Precision::float32:
        c.input = widened(cases::choose_case<float>(contract, defects, pick));
        break;
      case protocol::Precision::float64:
        c.input = widened(cases::choose_case<double>(contract, defects, pick));
        break;
      case protocol::Precision::long_double:
        c.input = widened(cases::choose_case<long double>(contract, defects, pick));
        break;
    }
    return c;
  }
  c.family = family_byte % 6;
  c.input.convention =
      contract.conventions[static_cast<std::size_t>(convention_byte) % contract.conventions.size()];
  Matrix4<double> m = Matrix4<double>::Identity();
  Vector4<double> plane = Vector4<double>::Zero();
  decode_numbers(in, c, c.input.convention, m, plane);
  c.input.matrix = m.cast<long double>();
  c.input.plane = plane.cast<long double>();
  c.input.family = contract_families(c).front();
  return c;
}

/// long double -> T without undefined behaviour: out-of-range finite values become +-infinity.
template <class T>
T narrow(long double x) {
  if (std::isfinite(x) && std::abs(x) > static_cast<long double>(std::numeric_limits<T>::max())) {
    return std::signbit(x) ? -std::numeric_limits<T>::infinity()
                           : std::numeric_limits<T>::infinity();
  }
  return static_cast<T>(x);
}

/// Whether OBLIQUE_FUZZ_DESCRIBE is set: then every case is printed before it is checked.
inline bool describing() {
  static const bool enabled = std::getenv("OBLIQUE_FUZZ_DESCRIBE") != nullptr;
  return enabled;
}

/// Prints M's rows and C, each number in T's shortest decimal and exact hex, indented by two.
template <class T>
void print_numbers(const Matrix4<T>& m, const Vector4<T>& plane, std::FILE* out) {
  using protocol::format_number;
  using protocol::Notation;
  for (int i = 0; i < 5; ++i) {
    std::string decimal, hex;
    for (int j = 0; j < 4; ++j) {
      const T x = i < 4 ? m(i, j) : plane(j);
      decimal += " " + format_number<T>(x);
      hex += (j ? " " : "") + format_number<T>(x, Notation::hex);
    }
    if (i < 4)
      std::fprintf(out, "  M row %d:%s  (%s)\n", i + 1, decimal.c_str(), hex.c_str());
    else
      std::fprintf(out, "  C:%s  (%s)\n", decimal.c_str(), hex.c_str());
  }
}

/// Prints the decoded case (OBLIQUE_FUZZ_DESCRIBE): what each byte chose, and the numbers as
/// made: a built case's in its scalar type, a decoded shape's in double.
inline void describe(const FuzzCase& c, std::FILE* out = stderr) {
  std::fprintf(out, "scalar %s, convention %s, method %s, family %s\n",
               std::string(protocol::precision_name(c.scalar)).c_str(),
               std::string(convention_name(c.input.convention)).c_str(),
               std::string(method_name(c.method)).c_str(), family_label(c).c_str());
  const auto print_in = [&](auto zero) {
    using T = decltype(zero);
    print_numbers<T>(c.input.matrix.cast<T>(), c.input.plane.cast<T>(), out);
  };
  if (c.family != kBuilt || c.scalar == protocol::Precision::float64) {
    print_in(0.0);
  } else if (c.scalar == protocol::Precision::float32) {
    print_in(0.0f);
  } else {
    print_in(0.0L);
  }
}

/// Prints the input as the function was given it: in its scalar type T (the decoder's scalar byte
/// picks T only for the project's own target).
template <class T>
void describe_input(const FuzzCase& c, const Matrix4<T>& m, const Vector4<T>& plane,
                    std::FILE* out = stderr) {
  std::fprintf(out, "input (%s, %s convention, %s projection):\n",
               std::string(protocol::scalar_name<T>()).c_str(),
               std::string(convention_name(c.input.convention)).c_str(), family_label(c).c_str());
  print_numbers(m, plane, out);
}

/// What the input allows, in words: an answer, no answer (its status), or an answer that lies
/// within rounding in T of a status boundary, where a refusal is right too.
template <class AnyProblem>
std::string allowed_words(const AnyProblem& problem, const char* scalar) {
  const Status exact = problem.exact_status();
  std::vector<Status> refusals;
  for (Status s : problem.acceptable_statuses()) {
    if (s != Status::ok && s != exact) refusals.push_back(s);
  }
  std::string out = exact == Status::ok
                        ? "the input has an answer"
                        : "the input has no answer: " + std::string(status_code(exact));
  if (!refusals.empty()) {
    out += exact == Status::ok ? "; it lies within rounding in " + std::string(scalar) +
                                     " of a boundary, so a refusal is right too: "
                               : "; right too: ";
    out += oracle::status_list(refusals);
  }
  return out;
}

/// Prints what the checker knows of the case and the answer, and every check that fails.
template <class T>
void explain(const oracle::Problem<T>& problem, const Answer<T>& outcome, std::FILE* out = stderr) {
  using protocol::format_number;
  std::fprintf(out, "%s (Skeel condition %s, kappa %s)\n",
               allowed_words(problem, std::string(protocol::scalar_name<T>()).c_str()).c_str(),
               format_number(problem.skeel_condition()).c_str(),
               format_number(problem.kappa().get_d()).c_str());
  if (outcome.status != Status::ok) return;
  for (int i = 0; i < 4; ++i) {  // also where the input has no answer: what was answered
    std::string row;
    for (int j = 0; j < 4; ++j) row += " " + format_number(outcome.projection(i, j));
    std::fprintf(out, "M' row %d:%s\n", i + 1, row.c_str());
  }
  if (problem.exact_status() != Status::ok) return;
  std::string row;
  for (const auto& v : problem.exact_row3()) row += " " + format_number(v.get_d());
  std::fprintf(out, "exact row 3:%s\n", row.c_str());
  cases::Checks every;
  every.every = true;
  for (const auto& f : oracle::judge(problem, outcome, every).checks) {
    if (!f.holds)
      std::fprintf(out, "%s: %s; residual %s, bound %s\n",
                   std::string(oracle::check_name(f.check)).c_str(),
                   oracle::relation_text(f).c_str(), oracle::residual_text(f).c_str(),
                   oracle::bound_text(f).c_str());
  }
}

/// One decoded case in T, judged for any number of implementations: one FilteredProblem (its
/// exact Problem, where needed, built once) and one judgement per distinct answer and checks
/// (implementations often answer alike, bit for bit, and judge() depends on nothing else).
template <class T>
class CaseJudge {
 public:
  explicit CaseJudge(const FuzzCase& c) : convention_(c.input.convention) {
    for (int i = 0; i < 16; ++i) m_(i / 4, i % 4) = narrow<T>(c.input.matrix(i / 4, i % 4));
    for (int i = 0; i < 4; ++i) plane_(i) = narrow<T>(c.input.plane(i));
  }
  const Matrix4<T>& matrix() const { return m_; }
  const Vector4<T>& plane() const { return plane_; }
  Convention convention() const { return convention_; }
  /// The filtered checker on the case (the exact one's verdicts, most without GMP; filtered.h).
  const oracle::FilteredProblem<T>& problem() {
    if (!problem_) problem_.emplace(m_, plane_, convention_);
    return *problem_;
  }
  oracle::Judgement judge(const Answer<T>& outcome, const cases::Checks& checks) {
    for (const Judged& j : judged_) {
      if (j.outcome.status == outcome.status &&
          same_bits(j.outcome.projection, outcome.projection) && same_checks(j.checks, checks))
        return j.judgement;
    }
    judged_.push_back(Judged{outcome, checks, oracle::judge(problem(), outcome, checks)});
    return judged_.back().judgement;
  }

 private:
  struct Judged {
    Answer<T> outcome;
    cases::Checks checks;
    oracle::Judgement judgement;
  };
  /// Bit for bit, the value bits only: x87's long double holds 10 bytes of value in 16, and the
  /// other 6 are whatever the memory held (comparing them made equal answers count as distinct,
  /// and the count of judgements vary from run to run).
  static bool same_bits(const Matrix4<T>& a, const Matrix4<T>& b) {
    constexpr std::size_t value_bytes =
        std::numeric_limits<T>::digits == 64 && sizeof(T) > 10 ? 10 : sizeof(T);
    for (int i = 0; i < 16; ++i) {
      if (std::memcmp(a.data() + i, b.data() + i, value_bytes) != 0) return false;
    }
    return true;
  }
  static bool same_checks(const cases::Checks& a, const cases::Checks& b) {
    return a.statuses == b.statuses && a.properties == b.properties &&
           a.row3_accuracy == b.row3_accuracy && a.every == b.every &&
           std::memcmp(&a.max_ulps, &b.max_ulps, sizeof a.max_ulps) == 0;
  }

  Matrix4<T> m_;
  Vector4<T> plane_;
  Convention convention_;
  std::optional<oracle::FilteredProblem<T>> problem_;
  std::vector<Judged> judged_;
};

/// Inputs judged in this process, and those left out by oracle::not_judged()'s reason (the
/// tally every way in keeps); printed to stderr at exit ("oblique: N inputs judged, ...").
inline void print_counts();

inline run::Tally& counts() {
  static run::Tally* c = [] {
    std::atexit(print_counts);
    return new run::Tally;  // never destroyed: print_counts may run after static destructors
  }();
  return *c;
}

inline void print_counts() {
  const run::Tally& c = counts();
  std::string line = "oblique: " + std::to_string(c.judged()) + " inputs judged";
  for (const auto& [why, n] : c.reasons()) line += ", " + std::to_string(n) + " left out: " + why;
  std::fprintf(stderr, "%s\n", line.c_str());
}

/// Whether the decoded case is one the contract claims, made so where it can be: a family it
/// lists (else counted, "family F: not in the contract"), and under unit planes its plane's
/// normal scaled to length 1 in double (a plane without a finite normal is counted left out).
/// The decoder makes its own planes, so the contract's places are not chosen here; its defects
/// are honoured in check() (defect_of()).
inline bool in_contract(FuzzCase& c, const Contract& contract) {
  const std::vector<cases::Family> families = contract_families(c);
  const bool claimed = std::any_of(families.begin(), families.end(), [&](cases::Family f) {
    return std::find(contract.families.begin(), contract.families.end(), f) !=
           contract.families.end();
  });
  if (!claimed) {
    counts().left_out({}, "family " + std::string(cases::family_name(families.front())) +
                              ": not in the contract");
    return false;
  }
  if (contract.planes == Planes::unit && c.family != kBuilt) {  // the builder scales its own
    Vector4<double> plane = c.input.plane.cast<double>();
    const double norm = plane.head<3>().norm();
    if (!std::isfinite(norm) || norm == 0 || !plane.allFinite()) {
      counts().left_out({}, "a plane without a finite normal (unit planes)");
      return false;
    }
    plane /= norm;
    c.input.plane = plane.cast<long double>();
  }
  return true;
}

/// The defect (cases::Defect, case_kinds.h) of which an input is an example, read from its
/// exact status: non-finite numbers (invalid_input), the camera in front (camera_not_behind_plane),
/// a plane that misses the view volume, a singular M, or an M within rounding of singular (an
/// answer exists, but singular_projection is acceptable); none for an input with an answer that
/// no such refusal is within rounding of.
template <class P>
std::optional<cases::Defect> defect_of(const P& problem) {
  using cases::Defect;
  switch (problem.exact_status()) {
    case Status::invalid_input: return Defect::non_finite;
    case Status::camera_not_behind_plane: return Defect::camera_in_front;
    case Status::plane_misses_view_volume: return Defect::misses_view_volume;
    case Status::singular_projection: return Defect::singular;
    default: break;
  }
  const std::vector<Status> acceptable = problem.acceptable_statuses();
  if (std::find(acceptable.begin(), acceptable.end(), Status::singular_projection) !=
      acceptable.end())
    return Defect::near_singular;
  return std::nullopt;
}

/// Runs `impl` on the case (in T) when it accepts it, and judges the answer with `checks`.
/// Inputs oracle::not_judged() leaves out for `checks.statuses` and `refusals` (under exact:
/// the refusals it implements, empty: all) are not given to it (and
/// counted), except that with `unanswerable` inputs without an exact answer are (there an answer
/// where none exists is the finding). On a violation: prints the case, the checker's view and the
/// property, then aborts. `judge` carries the case's problem and judgements from one
/// implementation to the next. An input that is an example of a defect not in `defects` (empty:
/// all; defect_of()) is not given to it either (counted "defect D: not in the contract").
template <class T>
void check(const FuzzCase& c, CaseJudge<T>& judge, const oracle::Implementation<T>& impl,
           const cases::Checks& checks, bool unanswerable = true,
           const std::vector<Status>& refusals = {},
           const std::vector<cases::Defect>& defects = {}) {
  const Matrix4<T>& m = judge.matrix();
  const Vector4<T>& plane = judge.plane();
  if (!impl.accepts(c.input.convention, m)) {
    counts().left_out({}, "refused by accepts (" + impl.name + ")");
    return;
  }
  if (!defects.empty()) {
    if (const std::optional<cases::Defect> d = defect_of(judge.problem());
        d && std::find(defects.begin(), defects.end(), *d) == defects.end()) {
      counts().left_out({},
                        "defect " + std::string(cases::defect_name(*d)) + ": not in the contract");
      return;
    }
  }
  if (const std::string why = oracle::not_judged(judge.problem(), checks.statuses, refusals);
      !why.empty() && !(unanswerable && judge.problem().exact_status() != Status::ok)) {
    counts().left_out({}, why);
    return;
  }
  counts().judged({});
  const Answer<T> outcome = impl.run(m, plane, c.input.convention);
  const oracle::Judgement judgement = judge.judge(outcome, checks);
  const oracle::Finding* violation = judgement.violation();
  if (!violation) return;
  describe_input<T>(c, m, plane);
  explain(judge.problem().exact(), outcome);
  std::fprintf(stderr, "oblique property violated: %s by %s (%s, %s, %s projection): it %s\n",
               std::string(oracle::check_name(violation->check)).c_str(), impl.name.c_str(),
               std::string(protocol::scalar_name<T>()).c_str(),
               std::string(convention_name(c.input.convention)).c_str(), family_label(c).c_str(),
               impl.answer_words(outcome.status).c_str());
  std::abort();
}

/// check() for one implementation.
template <class T>
void check(const FuzzCase& c, const oracle::Implementation<T>& impl, const cases::Checks& checks,
           bool unanswerable = true, const std::vector<Status>& refusals = {}) {
  CaseJudge<T> judge(c);
  check<T>(c, judge, impl, checks, unanswerable, refusals);
}

}  // namespace oblique::fuzzing
