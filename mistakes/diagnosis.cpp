// diagnose(): the search over the model's causes and the numerical routes (diagnosis.h); the
// words are diagnosis_text.cpp's.
#include "oblique/mistakes/diagnosis.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <functional>
#include <limits>
#include <memory>

#include "oblique/oblique.h"
#include "oblique/oracle/exact.h"
#include "oblique/oracle/exact_arithmetic.h"
#include "oblique/oracle/tolerance.h"
#include "oblique/projection.h"
#include "variant.h"

namespace oblique::mistakes {

using namespace oblique::oracle;  // NOLINT: the judge whose findings are diagnosed

namespace {

using oracle::exact::Rational;

/// A variant's exact answer on one case: a refusal, a non-finite matrix, or a matrix with a
/// bound on each entry (the rounding a careful implementation of that variant makes in T; 0 for
/// the rows it keeps). Undecided where the input is within rounding of a choice the variant makes
/// (C . Q near 0, a scale that cannot be bounded, an answer near overflow).
struct Exact {
  variant::Evaluation<Rational> e;
  bool decided = false;
  enum class Kind { refusal, non_finite, matrix } kind = Kind::refusal;
  oracle::exact::Mat values{}, bounds{};
};

template <class T>
Exact exact_answer(const Matrix4<T>& m, variant::Evaluation<Rational> evaluation) {
  Exact x;
  x.e = std::move(evaluation);
  const variant::Evaluation<Rational>& e = x.e;
  if (e.solve_failed) return x;
  if (e.status == Status::camera_not_behind_plane) {
    x.decided = true;
    return x;
  }
  if (e.non_finite) {
    x.decided = true;
    x.kind = Exact::Kind::non_finite;
    return x;
  }
  const oracle::exact::Mat mx = oracle::exact::to_rational(m);
  x.values = mx;
  for (auto& row : x.bounds) row.fill(0);
  if (e.unchanged) {
    x.decided = true;
    x.kind = Exact::Kind::matrix;
    return x;
  }
  // The error of C . Q as tolerance.h bounds it, for this variant's corner and the matrix S it
  // solves with; a closed form adds the magnitudes it sums (|C| . |Q| as it computes Q).
  const std::optional<oracle::exact::Mat> inverse = oracle::exact::inverse(e.solved);
  if (!inverse) return x;
  const oracle::exact::Mat abs_s = oracle::exact::abs(e.solved),
                           abs_inv = oracle::exact::abs(*inverse);
  const oracle::exact::Vec abs_c = oracle::exact::abs(e.c);
  const Rational numerator =
      oracle::tolerance::corner_dot_numerator(abs_c, oracle::exact::abs(e.q),
                                              oracle::exact::abs(e.c_clip),
                                              oracle::exact::abs(e.q_clip), abs_s, abs_inv) +
      (e.choices.closed_form ? oracle::exact::dot(abs_c, e.q_magnitude) : Rational(0));
  const int p = oracle::tolerance::precision_bits<T>();
  using Arithmetic = oracle::ExactArithmetic<T>;
  const Rational d_error = oracle::tolerance::corner_dot_error<Arithmetic>(
      numerator, oracle::tolerance::underflow_unit<T>());
  // A route (Knobs::via) forms its matrix's row 3 in T first: one more backward error on the
  // matrix it solves with, at most the solve's own (gamma of its roundings on the same entries),
  // so twice the bound covers it.
  const Rational d = oracle::exact::abs(e.d);
  if (d <= (e.routed ? 2 * d_error : d_error)) return x;  // the guard, the scale: not decided
  if (e.choices.closed_form && !e.perspective_shape) {
    // The closed form on another shape is not M^-1 Q': a corner sign read from a C' component
    // within its solve's error (gamma(12) (|S^-T| |S^T| |C'|)_i) may come out either way in T,
    // and C . Q with it, by far more than d's error.
    const oracle::exact::Vec spread = oracle::exact::mul(
        oracle::exact::transpose(abs_inv),
        oracle::exact::mul(oracle::exact::transpose(abs_s), oracle::exact::abs(e.c_clip)));
    const Rational solve_gamma = oracle::tolerance::gamma(oracle::tolerance::kSolveRoundings, p);
    for (int i = 0; i < 3; ++i) {
      if (e.sign_of_computed[i] &&
          oracle::exact::abs(e.c_clip[i]) <=
              solve_gamma * spread[i] + oracle::tolerance::underflow_unit<T>())
        return x;
    }
  }
  if (e.status == Status::plane_misses_view_volume) {
    x.decided = true;
    return x;
  }
  const Rational scale =
      *oracle::tolerance::scale_error<Arithmetic>(d_error, d);  // d > d_error: eps < 1
  const Rational largest = oracle::exact::to_rational(std::numeric_limits<T>::max()) / 256;
  for (int row : {2, 3}) {
    if (row == 3 && !e.row4_changed) continue;
    const int r = row == 2 ? e.r3 : 1, t = row == 2 ? e.t3 : 1, den = row == 2 ? e.den : 1;
    const oracle::exact::Vec m4 = variant::row_m4(mx, row == 2 && e.m4_assumed);
    for (int i = 0; i < 4; ++i) {
      const Rational ac = r * e.a * e.c[i];
      x.values[row][i] = (ac + t * m4[i]) / den;
      x.bounds[row][i] = oracle::tolerance::row3_entry_bound<Arithmetic>(
                             oracle::exact::abs(ac), oracle::exact::abs(t * m4[i]), scale,
                             oracle::tolerance::underflow_unit<T>()) /
                         den;
      // The way back, in T: row 3 less a multiple of M_4, times a power of two: one rounding
      // more of each term (the halving is exact).
      if (e.routed)
        x.bounds[row][i] += oracle::tolerance::gamma(2, oracle::tolerance::precision_bits<T>()) *
                            (oracle::exact::abs(ac) + oracle::exact::abs(t * m4[i])) / den;
      if (oracle::exact::abs(x.values[row][i]) >= largest)
        return x;  // near overflow: out_of_range too
    }
  }
  x.decided = true;
  x.kind = Exact::Kind::matrix;
  return x;
}

enum class Match { undecided, agrees, differs };

/// `answers_only`: the program has no refusals, so its answer where the cause refuses says
/// nothing either way.
template <class T>
Match compare(const Observation<T>& o, const Exact& x, bool answers_only = false) {
  if (!x.decided) return Match::undecided;
  // Refusals agree by name; another refusal than the cause's is no evidence either way (a
  // program may name its refusals otherwise, or refuse out_of_range within rounding).
  if (x.kind == Exact::Kind::refusal) {
    if (o.status == Status::ok) return answers_only ? Match::undecided : Match::differs;
    return o.status == x.e.status ? Match::agrees : Match::undecided;
  }
  if (o.status != Status::ok) return Match::differs;
  if (x.kind == Exact::Kind::non_finite) {
    if (!all_finite(o.projection)) return Match::agrees;
    // A NaN sign of a C' component that is 0 exactly: computed in T it may round to either sign
    // (both corners equally far), and the answer is then finite.
    return x.e.nan_sign_of_computed ? Match::undecided : Match::differs;
  }
  if (!all_finite(o.projection)) return Match::differs;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      if (oracle::exact::abs(oracle::exact::to_rational(o.projection(i, j)) - x.values[i][j]) >
          x.bounds[i][j])
        return Match::differs;
    }
  }
  return Match::agrees;
}

/// Whether two decided answers cannot both be the one a careful implementation gives.
bool distinct(const Exact& a, const Exact& b) {
  if (!a.decided || !b.decided) return false;
  if (a.kind != b.kind) return true;
  if (a.kind != Exact::Kind::matrix) return false;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      if (oracle::exact::abs(a.values[i][j] - b.values[i][j]) > a.bounds[i][j] + b.bounds[i][j])
        return true;
    }
  }
  return false;
}

/// A few cases of each shape where the catalogue's mistakes part: mirrored, flipped, off-axis,
/// shifted, left-handed and orthographic matrices, with planes of every corner sign, head-on,
/// through and in front of the camera and beyond the far plane.
template <class T>
struct PanelCase {
  Matrix4<T> matrix;
  Vector4<T> plane;
  cases::Family family;
};

template <class T>
std::vector<PanelCase<T>> panel(Convention convention) {
  using cases::Family;
  struct Shape {
    Matrix4<T> m;
    Family family;
    bool left_handed;
  };
  const Matrix4<T> p = frustum<T>(-1, 1, -0.75, 0.75, 1, 64, convention);
  Matrix4<T> x = p, y = p, xy = p, s = p, left = p, left_x = p;
  x.row(0) *= T(-1);
  y.row(1) *= T(-1);
  xy.row(0) *= T(-1);
  xy.row(1) *= T(-1);
  s(0, 3) = T(0.25);  // a lens shift: M14, M24
  s(1, 3) = T(-0.125);
  Matrix4<T> xs = x, ys = y;
  xs.col(3) = ys.col(3) = s.col(3);
  xs(0, 3) = -xs(0, 3);
  left.col(2) *= T(-1);  // a left-handed camera: z negated
  // A deep frustum (f / n = 10^7), right- and left-handed: where a route that forms 1 + n / (f - n)
  // in T (reversed Z taken forward) loses every bit of it.
  const Matrix4<T> deep =
      frustum<T>(T(-0.01), T(0.01), T(-0.0075), T(0.0075), T(0.01), T(100000), convention);
  Matrix4<T> deep_left = deep;
  deep_left.col(2) *= T(-1);
  left_x = left;
  left_x.row(0) *= T(-1);  // its mirror pass, x flipped (Direct3D-style engines)
  // The camera turned about y and x (P R): C' mixes C's components (a head-on plane has
  // C'_x, C'_y != 0).
  Matrix4<T> about_y = Matrix4<T>::Identity(), about_x = Matrix4<T>::Identity();
  about_y(0, 0) = about_y(2, 2) = about_x(1, 1) = about_x(2, 2) = T(0.75);
  about_y(0, 2) = about_x(2, 1) = T(0.5);
  about_y(2, 0) = about_x(1, 2) = T(-0.5);
  const Matrix4<T> turned = p * about_y * about_x;
  const Shape shapes[] = {
      {p, Family::perspective, false},
      {x, Family::x_flipped, false},
      {y, Family::y_flipped, false},
      {xy, Family::xy_flipped, false},
      {frustum<T>(-0.5, 1.5, -0.25, 1.25, 1, 64, convention), Family::off_axis, false},
      // leaning left and down (M13, M23 < 0): a VR eye, a tiled screenshot's lower left tile
      {frustum<T>(-1.5, 0.5, -1.25, 0.25, 1, 64, convention), Family::off_axis, false},
      {s, Family::stereo_shift, false},
      {xs, Family::general, false},
      {ys, Family::general, false},
      {left, Family::left_handed, true},
      {left_x, Family::left_handed_x_flipped, true},
      {deep, Family::perspective, false},
      {deep_left, Family::left_handed, true},
      {orthographic<T>(-2, 2, -1.5, 1.5, 1, 64, convention), Family::orthographic, false},
      // an orthographic volume reaching behind the eye: C'_z < 0 for the last plane below
      {orthographic<T>(-2, 2, -2, 2, -5, 10, convention), Family::orthographic, false},
      {turned, Family::general, false},
  };
  // Every corner sign, head-on, through and in front of the camera, beyond the far plane (head-on,
  // and tilted: no zero component of C', so no corner sign is 0 there), nearer than the near
  // plane (where a corner on the near face may still be on C's kept side), steep and near (where
  // the shift, dropped or negated, decides C'_z's sign), and along the view axis (C_z = 0: C'_z = 0
  // when orthographic).
  const T planes[][4] = {{0.25, 0.5, -1, -4},     {-0.25, 0.5, -1, -4},   {0.25, -0.5, -1, -4},
                         {-0.25, -0.5, -1, -4},   {0, 0, -1, -4},         {0.25, 0.5, -1, 0},
                         {0.25, 0.5, -1, 2},      {0, 0, -1, -100},       {1, 1, 0.125, -1},
                         {0.125, 0.25, -1, -100}, {-0.25, 0.5, -1, -0.5}, {-1, 0.5, -1, -0.125},
                         {1, -0.5, -1, -0.125},   {1, 0.5, 0, -2}};
  static_assert(std::size(shapes) * std::size(planes) + 1 == kPanelCasesPerConvention);
  std::vector<PanelCase<T>> out;
  for (const Shape& shape : shapes) {
    for (const auto& c : planes) {
      out.push_back(PanelCase<T>{
          shape.m, Vector4<T>(c[0], c[1], shape.left_handed ? -c[2] : c[2], c[3]), shape.family});
    }
  }
  // C'_z = 0 exactly on a matrix a closed form still answers finitely: a sign computed at 0 (x /
  // |x|) shows there and nowhere else once the corner's x and y signs are fixed. (On the
  // perspective shape C'_z = C_w / M34, so C'_z = 0 only for a plane through the eye.) M shifted,
  // every entry a binary fraction; C = M^T (-1, 1, 0, 1) = (-1, 1, -1, -0.375), exact.
  Matrix4<T> shifted = Matrix4<T>::Zero();
  shifted(0, 0) = shifted(1, 1) = T(1);
  shifted(0, 3) = T(0.25);
  shifted(1, 3) = T(-0.125);
  shifted(2, 2) = shifted(3, 2) = T(-1);
  shifted(2, 3) = T(-2);
  out.push_back(PanelCase<T>{shifted, Vector4<T>(-1, 1, -1, -0.375), Family::general});
  return out;
}

/// One case and what the causes tried on it have computed: the solves and, for each distinct
/// decision, the exact answer (thousands of causes are tried, and on one case they make few
/// distinct decisions; the correct method's is one of them).
template <class T>
struct Case {
  Observation<T> seen;
  bool answers_only = false;  ///< the program has no refusals (diagnose()'s answers_only)
  std::shared_ptr<variant::SolveMemo<Rational>> solves;
  /// Each decision tried on this case: its exact answer, whether the observed answer is it, and
  /// (once asked) whether it differs from the correct one.
  struct Tried {
    variant::Decision decision;
    Exact answer;
    Match match;
    mutable std::optional<bool> differs_from_right;
  };
  std::shared_ptr<std::deque<Tried>> answers;
};

template <class T>
Case<T> make_case(const Observation<T>& o, bool answers_only) {
  Case<T> k;
  k.answers_only = answers_only;
  k.seen = o;
  k.solves = std::make_shared<variant::SolveMemo<Rational>>();
  k.answers = std::make_shared<std::deque<typename Case<T>::Tried>>();
  // Fills the memo with M, C and their signs in rationals (and the correct method's solves).
  variant::evaluate<Rational>(o.matrix, o.plane, o.convention, variant::Knobs{}, k.solves.get());
  return k;
}

/// The exact answer of the variant with `knobs` on case `k`, compared with the answer observed
/// and the correct one: computed once per decision.
template <class T>
const typename Case<T>::Tried& tried(const Case<T>& k, const variant::Knobs& knobs) {
  const Observation<T>& o = k.seen;
  variant::SolveMemo<Rational>& memo = *k.solves;
  const variant::Decision d = variant::decide(
      knobs, o.convention, memo.perspective, memo.c_sign, memo.entry_sign,
      [&memo](const std::array<int, 4>& solved) { return variant::clip_signs(memo, solved); });
  for (const auto& t : *k.answers) {
    if (t.decision == d) return t;
  }
  Exact x = exact_answer(o.matrix, variant::evaluate<Rational>(o.matrix, o.plane, o.convention,
                                                               knobs, k.solves.get()));
  const Match match = compare(o, x, k.answers_only);
  k.answers->push_back(typename Case<T>::Tried{d, std::move(x), match, std::nullopt});
  return k.answers->back();
}

/// The correct method's exact answer on case `k`.
template <class T>
const Exact& right_answer(const Case<T>& k) {
  return tried(k, variant::Knobs{}).answer;
}

/// Whether the answer of `t` (tried on `k`) cannot be the correct one (distinct()).
template <class T>
bool differs_from_right(const Case<T>& k, const typename Case<T>::Tried& t) {
  if (!t.differs_from_right) {
    const typename Case<T>::Tried& right = tried(k, variant::Knobs{});
    t.differs_from_right =
        &right != &t && !(right.decision == t.decision) && distinct(t.answer, right.answer);
  }
  return *t.differs_from_right;
}

template <class T>
bool explains(const variant::Knobs& knobs, const std::vector<Case<T>>& cases) {
  bool evidence = false;
  for (const Case<T>& k : cases) {
    const typename Case<T>::Tried& t = tried(k, knobs);
    if (t.match == Match::differs) return false;
    if (t.match == Match::agrees && k.seen.wrong && differs_from_right(k, t)) evidence = true;
  }
  return evidence;
}

void add_differences(const variant::Choices& mine, const variant::Choices& right,
                     std::vector<ChoiceDifference>& out) {
  auto add = [&out](Choice c, double a, double b) {
    if (a != b) out.push_back(ChoiceDifference{c, a, b});
  };
  add(Choice::camera_guard, mine.refused_camera, right.refused_camera);
  add(Choice::head_on, mine.head_on_skipped, right.head_on_skipped);
  if (mine.refused_camera || right.refused_camera || mine.head_on_skipped || right.head_on_skipped)
    return;
  add(Choice::solve, mine.solve_changed(), right.solve_changed());
  add(Choice::closed_form, mine.closed_form, right.closed_form);
  add(Choice::nan_sign, mine.nan_sign, right.nan_sign);
  add(Choice::corner_guard, mine.refused_corner, right.refused_corner);
  add(Choice::sign_x, mine.sx, right.sx);
  add(Choice::sign_y, mine.sy, right.sy);
  add(Choice::face, mine.z_twice / 2.0, right.z_twice / 2.0);
  add(Choice::formula, static_cast<int>(mine.formula), static_cast<int>(right.formula));
  add(Choice::row4, mine.note_flip, right.note_flip);
  add(Choice::factor, mine.numerator, right.numerator);
  add(Choice::form, mine.t3, right.t3);
  add(Choice::q_z, mine.q_z_assumed, right.q_z_assumed);
  add(Choice::q_w, mine.left_handed_qw, right.left_handed_qw);
  add(Choice::m4, mine.m4_assumed, right.m4_assumed);
  add(Choice::route, mine.routed, right.routed);
}

std::optional<std::array<double, 4>> row_of(const Exact& x, int row) {
  if (!x.decided || x.kind == Exact::Kind::refusal) return std::nullopt;
  std::array<double, 4> out;
  for (int i = 0; i < 4; ++i) {
    out[i] = x.kind == Exact::Kind::non_finite ? std::numeric_limits<double>::quiet_NaN()
                                               : x.values[row][i].get_d();
  }
  return out;
}

/// A cause tried: mistakes that change no choice in common, and the knobs they set together.
struct Candidate {
  std::vector<Mistake> mistakes;
  variant::Knobs knobs;
};

/// The convention a mistake of the formula (its formula, factor or form) is made in: the
/// mistakes a route through that convention makes a different program of. None for the others
/// (geometric choices, guards: the same on every route, as the far corner and the planes are).
std::optional<Convention> formula_mistake_in(Mistake mistake) {
  switch (mistake) {
    case Mistake::zero_one_formula_on_gl:
    case Mistake::zero_one_factor_on_gl:
    case Mistake::zero_one_form_on_gl: return Convention::gl;
    case Mistake::gl_formula_on_zero_one:
    case Mistake::gl_form_on_zero_one:
    case Mistake::gl_factor_on_zero_one: return Convention::zero_one;
    default: return std::nullopt;
  }
}

/// Every cause of up to kMostMistakes mistakes, by size, and each of them that changes the
/// formula on a route through another convention (all_routes), one size up: each one a different
/// program (causes whose knobs are a smaller cause's are left out: that one is the name).
const std::vector<std::vector<Candidate>>& candidates_by_size() {
  static const std::vector<std::vector<Candidate>> sizes = [] {
    std::vector<std::vector<Candidate>> out(kMostChoices);
    std::vector<variant::Knobs> seen;
    auto add = [&](std::vector<Mistake> mistakes) {
      variant::Knobs knobs = variant::knobs_of(mistakes);
      if (std::find(seen.begin(), seen.end(), knobs) != seen.end()) return;
      seen.push_back(knobs);
      out[mistakes.size() - 1].push_back(Candidate{std::move(mistakes), knobs});
    };
    // Each size in turn, so that a set whose knobs a smaller one has is left out.
    for (int size = 1; size <= kMostMistakes; ++size) {
      std::vector<Mistake> chosen;
      std::function<void(std::size_t, unsigned)> choose = [&](std::size_t from, unsigned used) {
        if (static_cast<int>(chosen.size()) == size) {
          add(chosen);
          return;
        }
        for (std::size_t i = from; i < std::size(all_mistakes); ++i) {
          const unsigned changes = choices_changed(all_mistakes[i]);
          if (used & changes) continue;
          chosen.push_back(all_mistakes[i]);
          choose(i + 1, used | changes);
          chosen.pop_back();
        }
      };
      choose(0, 0);
      // The causes of this size made on a route, a choice more: those with a mistake of the
      // formula, each made in the route's convention (on the route every matrix runs there, so a
      // mistake made in another never shows, and the cause is a smaller one's program).
      for (const Candidate& c : std::vector<Candidate>(out[size - 1])) {
        unsigned used = 0;
        for (Mistake m : c.mistakes) used |= choices_changed(m);
        for (Mistake route : all_routes) {
          const Convention via = *variant::knobs_of(route).via;
          bool formula = false, elsewhere = false;
          for (Mistake m : c.mistakes) {
            if (const auto in = formula_mistake_in(m)) (*in == via ? formula : elsewhere) = true;
          }
          if (!formula || elsewhere || (used & choices_changed(route))) continue;
          std::vector<Mistake> routed = c.mistakes;
          routed.push_back(route);
          add(std::move(routed));
        }
      }
    }
    return out;
  }();
  return sizes;
}

/// The smallest causes that explain every answer of `cases`: each mistake alone, or where none
/// does, each two together, or each three; with `routes`, each also made on a route (a choice
/// more). Routes are tried where the panel was asked: a route rescales row 3 through another
/// range, and with a mistake of the formula that is two choices more that one case alone (a fuzz
/// input, a scene's few passes) fits by chance.
template <class T>
std::vector<std::vector<Mistake>> causes_of(const std::vector<Case<T>>& cases, bool routes) {
  std::vector<std::vector<Mistake>> out;
  for (const std::vector<Candidate>& size : candidates_by_size()) {
    for (const Candidate& c : size) {
      if (!routes && c.knobs.via) continue;
      if (explains<T>(c.knobs, cases)) out.push_back(c.mistakes);
    }
    if (!out.empty()) return out;
  }
  return out;
}

/// The numerical route that reproduces every answer of `cases` (numerical_routes.h): computed in
/// T, it gives each answer within twice the careful rounding bound of the correct one (plus a
/// few ulps: the program rounds in its own order), or the same refusal, or a non-finite matrix
/// where the answer is one; and on some wrong answer it is not the correct answer.
template <class T>
std::optional<NumericalCause> numerical_cause_of(const std::vector<Case<T>>& cases) {
  const int p = std::numeric_limits<T>::digits;
  for (NumericalRoute route : all_numerical_routes) {
    bool fits = true;
    std::optional<NumericalCause> found;
    for (const Case<T>& k : cases) {
      const Observation<T>& o = k.seen;
      const Exact& right = right_answer(k);
      if (!right.decided) continue;
      const RouteAnswer<T> r = route_answer(route, o.matrix, o.plane, o.convention);
      const bool finite = all_finite(r.projection);
      // A program that checks its answer is finite refuses out_of_range where the route's is not.
      const bool refused_non_finite = !finite && o.status == Status::out_of_range;
      if (r.status != Status::ok || (o.status != Status::ok && !refused_non_finite)) {
        fits = r.status == o.status;
        if (!fits) break;
        continue;
      }
      if (!refused_non_finite && finite != all_finite(o.projection)) {
        fits = false;
        break;
      }
      NumericalCause measured{route, !finite, 0, p, p};
      // The rounding bound of the matrix the route modifies carefully (the converted one).
      const bool converted = r.modified != o.matrix || r.modified_convention != o.convention;
      Exact modified;
      if (converted) {
        modified = exact_answer(r.modified, variant::evaluate<Rational>(r.modified, o.plane,
                                                                        r.modified_convention, {}));
        // Where the converted matrix's own answer is within rounding of a choice (C . Q near 0 in
        // T), the route taken in another order of operations may give anything: no evidence.
        if (!modified.decided) continue;
      }
      const bool right_matrix = right.kind == Exact::Kind::matrix;
      // Evidence needs both the route's answer and the one observed beyond the correct answer's
      // rounding bound (a right answer with noise is no route's).
      bool wrong_route = !finite || !right_matrix, wrong_answer = !finite || !right_matrix;
      for (int i = 0; finite && i < 4; ++i) {
        for (int j = 0; j < 4; ++j) {
          const T v = r.projection(i, j);
          const Rational ulp = oracle::exact::to_rational(
              std::nextafter(std::abs(v), std::numeric_limits<T>::infinity()) - std::abs(v));
          const Rational route_value = oracle::exact::to_rational(v);
          const Rational bound = right_matrix ? right.bounds[i][j] : Rational(0);
          const Rational inner =
              modified.kind == Exact::Kind::matrix ? modified.bounds[i][j] : Rational(0);
          if (oracle::exact::abs(oracle::exact::to_rational(o.projection(i, j)) - route_value) >
              2 * (bound > inner ? bound : inner) + 8 * ulp) {
            fits = false;
            break;
          }
          if (right_matrix && oracle::exact::abs(route_value - right.values[i][j]) > bound)
            wrong_route = true;
          if (right_matrix && oracle::exact::abs(oracle::exact::to_rational(o.projection(i, j)) -
                                                 right.values[i][j]) > bound)
            wrong_answer = true;
        }
        if (!fits) break;
      }
      if (!fits) break;
      if (!o.wrong || !wrong_route || !wrong_answer || found) continue;
      if (finite && right_matrix) {
        // Against C's multiple in row 3 (row 3 less its M_4 part): the far plane's scale.
        double worst = 0, largest = 0;
        for (int j = 0; j < 4; ++j) {
          const Rational& v = right.values[2][j];
          worst = std::max(worst, std::abs(static_cast<double>(o.projection(2, j)) - v.get_d()));
          largest = std::max(
              largest,
              std::abs(
                  Rational(v - right.e.t3 * oracle::exact::to_rational(o.matrix(3, j))).get_d()));
        }
        measured.relative_error = largest > 0 ? worst / largest : 0;
        const double kept = measured.relative_error > 0 ? -std::log2(measured.relative_error) : p;
        measured.bits_lost = std::clamp(p - static_cast<int>(std::floor(kept)), 0, p);
      }
      found = measured;
    }
    if (fits && found) return found;
  }
  return std::nullopt;
}

/// Each family's answers diagnosed alone, where they part by family: some family with every
/// answer right and some with a wrong one. Empty otherwise (one family, or wrong everywhere).
template <class T>
std::vector<FamilyDiagnosis> by_family(const std::vector<Case<T>>& cases, bool routes) {
  std::vector<FamilyDiagnosis> out;
  for (cases::Family family : cases::all_families) {
    std::vector<Case<T>> group;
    for (const Case<T>& k : cases) {
      if (k.seen.family == family) group.push_back(k);
    }
    if (group.empty()) continue;
    FamilyDiagnosis f;
    f.family = family;
    f.seen = static_cast<int>(group.size());
    f.wrong = static_cast<int>(
        std::count_if(group.begin(), group.end(), [](const Case<T>& k) { return k.seen.wrong; }));
    if (f.wrong > 0) f.causes = causes_of(group, routes);
    if (f.wrong > 0 && f.causes.empty()) {
      for (const Case<T>& k : group) {
        const Observation<T>& o = k.seen;
        if (!o.wrong || o.status != Status::ok || !all_finite(o.projection)) continue;
        const AnswerGeometry g = answer_geometry(o.matrix, o.plane, o.convention, o.projection);
        if (g.described) f.geometry = g;
        break;
      }
    }
    out.push_back(std::move(f));
  }
  const bool some_right =
      std::any_of(out.begin(), out.end(), [](const FamilyDiagnosis& f) { return f.wrong == 0; });
  const bool some_wrong =
      std::any_of(out.begin(), out.end(), [](const FamilyDiagnosis& f) { return f.wrong > 0; });
  if (!some_right || !some_wrong) out.clear();
  return out;
}

}  // namespace

std::vector<std::vector<Mistake>> causes_tried(int size) {
  std::vector<std::vector<Mistake>> out;
  if (size < 1 || size > kMostChoices) return out;
  for (const Candidate& c : candidates_by_size()[size - 1]) out.push_back(c.mistakes);
  return out;
}

/// Whether every answer of `cases` leaves M as it was but for its third column, and at least
/// one changes that column off row 3 and is wrong: whatever formula the function ran, it wrote
/// its oblique row where the other layout keeps row 3 (the modification is a row's; M^T's row 3
/// read back in the other layout is M's column 3).
template <class T>
bool column_three_written(const std::vector<Case<T>>& cases) {
  bool wrong_written = false;
  for (const Case<T>& k : cases) {
    const Observation<T>& o = k.seen;
    if (o.status != Status::ok) continue;
    bool written = false;
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) {
        const bool same = o.projection(i, j) == o.matrix(i, j);
        if (j != 2 && !same) return false;
        if (j == 2 && i != 2 && !same) written = true;
      }
    }
    wrong_written = wrong_written || (written && o.wrong);
  }
  return wrong_written;
}

/// Whether every answer of `cases` is the correct modification of M^T transposed back (a
/// refusal where that refuses, else its matrix to half of T's digits), and at least one of them
/// a wrong answer, or column_three_written(): the matrix read in the other layout.
template <class T>
bool transposed_layout_explains(const std::vector<Case<T>>& cases) {
  if (column_three_written(cases)) return true;
  const T tolerance = std::sqrt(std::numeric_limits<T>::epsilon()) * T(4);
  bool wrong_explained = false;
  for (const Case<T>& k : cases) {
    const Observation<T>& o = k.seen;
    const ObliqueResult<T> r = apply<T>(Matrix4<T>(o.matrix.transpose()), o.plane, o.convention);
    if ((o.status == Status::ok) != r.ok()) return false;
    if (!r.ok()) continue;  // a refusal where the transposed one refuses: any refusal
    const Matrix4<T> expected = r.projection.transpose();
    const T scale = std::max(expected.cwiseAbs().maxCoeff(), T(1));
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        if (!(std::abs(o.projection(i, j) - expected(i, j)) <= tolerance * scale)) return false;
    wrong_explained = wrong_explained || o.wrong;
  }
  return wrong_explained;
}

template <class T>
Diagnosis diagnose(const std::vector<Observation<T>>& seen, const Probe<T>& probe,
                   bool answers_only) {
  Diagnosis out;
  std::vector<Case<T>> cases;
  auto add_case = [&cases, answers_only](const Observation<T>& o) {
    if (!all_finite(o.matrix) || !all_finite(o.plane)) return;  // invalid input: no mistake
    cases.push_back(make_case(o, answers_only));
  };
  for (const Observation<T>& o : seen) add_case(o);
  if (std::none_of(cases.begin(), cases.end(), [](const Case<T>& k) { return k.seen.wrong; }))
    return out;
  out.ran = true;
  if (probe) {
    // Every convention: a mistake may show on another convention than the finding's (code that
    // swaps the two formulas). The probe declines the conventions the program does not serve.
    for (Convention convention : all_conventions) {
      for (const PanelCase<T>& k : panel<T>(convention)) {
        if (std::optional<Observation<T>> o = probe(k.matrix, k.plane, convention, k.family)) {
          if (!o->family) o->family = k.family;
          add_case(*o);
          ++out.probed;
        }
      }
    }
  }
  // Wrong answers first: most causes are ruled out there.
  std::stable_partition(cases.begin(), cases.end(), [](const Case<T>& k) { return k.seen.wrong; });
  out.seen = static_cast<int>(cases.size());
  out.wrong = static_cast<int>(
      std::count_if(cases.begin(), cases.end(), [](const Case<T>& k) { return k.seen.wrong; }));
  out.causes = causes_of(cases, static_cast<bool>(probe));
  if (out.causes.empty()) {
    out.transposed_layout = transposed_layout_explains(cases);
    if (out.transposed_layout) return out;
    out.numerical = numerical_cause_of(cases);
    if (out.numerical) return out;
    out.families = by_family(cases, static_cast<bool>(probe));
    for (const Case<T>& k : cases) {
      const Observation<T>& o = k.seen;
      if (!o.wrong || o.status != Status::ok || !all_finite(o.projection)) continue;
      const AnswerGeometry g = answer_geometry(o.matrix, o.plane, o.convention, o.projection);
      if (g.described) out.geometry = g;
      break;
    }
    return out;
  }
  const variant::Knobs knobs = variant::knobs_of(out.causes.front());
  bool evidence_taken = false;
  for (const Case<T>& k : cases) {
    const Observation<T>& o = k.seen;
    const typename Case<T>::Tried& t = tried(k, knobs);
    const Exact& x = t.answer;
    if (!x.decided) continue;
    ++out.decided;
    const bool differs = differs_from_right(k, t);
    const Exact& right = right_answer(k);
    if (o.wrong && differs) ++out.wrong_where_it_differs;
    if (!o.wrong && !differs && right.decided) ++out.right_where_it_agrees;
    if (evidence_taken || !o.wrong || !differs || compare(o, x, answers_only) != Match::agrees)
      continue;
    evidence_taken = true;
    out.answered = o.status;
    out.mistaken = x.kind == Exact::Kind::refusal ? x.e.status : Status::ok;
    out.right = right.kind == Exact::Kind::refusal ? right.e.status : Status::ok;
    out.row = x.e.row4_changed ? 3 : 2;
    if (o.status == Status::ok) {
      std::array<double, 4> row;
      for (int i = 0; i < 4; ++i) row[i] = static_cast<double>(o.projection(out.row, i));
      out.answered_row = row;
    }
    out.mistaken_row = row_of(x, out.row);
    out.right_row = row_of(right, out.row);
    add_differences(x.e.choices, right.e.choices, out.differences);
  }
  return out;
}

template Diagnosis diagnose<float>(const std::vector<Observation<float>>&, const Probe<float>&,
                                   bool);
template Diagnosis diagnose<double>(const std::vector<Observation<double>>&, const Probe<double>&,
                                    bool);
template Diagnosis diagnose<long double>(const std::vector<Observation<long double>>&,
                                         const Probe<long double>&, bool);

}  // namespace oblique::mistakes
