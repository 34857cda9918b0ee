// The one case builder: a projection of a family, a plane at a place, a valid case, and an input
// spoiled by a defect, each built from integer picks. Every way in feeds it: RapidCheck's choices
// (generators.h, so failures shrink), a fuzz input's bytes (oblique/fuzzing/driver.h) and verify's
// seeded draws (through RapidCheck), so each draws the same families and places and honours the
// same contract (choose_case()).
//
// Every pick's zero is the simplest value (RapidCheck shrinks integers toward the low end of their
// range), so a shrunk counterexample reads like 1, 0.5, 1e-6, not like 0.7368421052631579.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "oblique/cases/case_kinds.h"
#include "oblique/cases/contract.h"
#include "oblique/depth_convention.h"
#include "oblique/plane.h"
#include "oblique/util/eigen_layout.h"

namespace oblique::cases {

/// One input, the one case type of every way in: the numbers and what they were built as.
template <class T>
struct Case {
  Family family = Family::perspective;
  Convention convention = Convention::gl;
  Place place = Place::typical;
  /// The defect that spoiled a valid case of family, convention and place (spoil()): an input
  /// without an answer, or next to one; none for a valid-looking case.
  std::optional<Defect> defect;
  Matrix4<T> matrix = Matrix4<T>::Identity();
  Vector4<T> plane = Vector4<T>::Zero();
};

/// What a case was built as, in words: its place, or "no answer: DEFECT".
template <class T>
std::string case_kind(const Case<T>& c) {
  return c.defect ? "no answer: " + std::string(defect_name(*c.defect))
                  : std::string(place_name(c.place));
}

/// An integer in [lo, hi) (lo < hi): RapidCheck's choice, or a fuzz input's bytes.
using Pick = std::function<int(int lo, int hi)>;

// Compiled in oblique::cases; declared in its Eigen layout's namespace (util/eigen_layout.h), since
// a Case holds matrices after smaller members.
inline namespace OBLIQUE_EIGEN_LAYOUT {

/// A projection of `family` in `convention`, its parameters from readable picks:
/// near 1e-6 .. 10, far / near 1.5 .. ~1e12 (or infinite), symmetric to fully off-axis.
///
/// Every sign an engine's matrix takes is drawn: a frustum leans either way in x and y (M13,
/// M23: a VR eye has more field of view on one side, a tiled screenshot's row above or below the
/// axis), a stereo eye leans and shifts either way (M14, M24), a box is centred or off-centre
/// either way, and the flipped and jittered frustums lean too. Which signs: `round`'s pattern
/// (round % 4: bit 0 the x sign, bit 1 the y sign), so that a run that cycles its rounds draws
/// every pattern of every family (valid_case_in() passes the run's round); picked when negative.
/// Rounds 0 .. kRounds - 1 give every pattern of every family.
template <class T>
Matrix4<T> build_projection(Family family, Convention convention, int round, const Pick& pick);
inline constexpr int kRounds = 24;

/// A plane at `place` for the projection m. The camera is behind it (C_w < 0) by construction
/// except where rounding or the family's geometry prevents it; properties filter those with the
/// exact status.
template <class T>
Vector4<T> build_plane(const Matrix4<T>& m, Convention convention, Place place, const Pick& pick);

/// A valid-looking case: build_projection() then build_plane().
template <class T>
Case<T> build_case(Family family, Convention convention, Place place, int round, const Pick& pick);

/// `c` spoiled by `defect` (the result's defect): an input that has no answer, or sits next to
/// one that has none.
template <class T>
Case<T> spoil(Case<T> c, Defect defect, const Pick& pick);

/// C scaled to a unit normal (in long double, rounded once), as engines build planes; a plane
/// with a non-finite entry or a zero normal is left as it is.
template <class T>
Vector4<T> unit_normal(const Vector4<T>& c);

/// A case of a resolved contract (oblique::resolved()) from picks alone, as a fuzz input draws
/// one: a family, convention and place of its lists, a round, and, when `defects` is true and the
/// contract lists defects, one input in five spoiled by one of them; the plane scaled to a unit
/// normal when its planes are unit. RapidCheck draws the same through valid_case_for() and
/// invalid_case_for() (with its own spread over the lists).
template <class T>
Case<T> choose_case(const Contract& contract, bool defects, const Pick& pick);

#define OBLIQUE_CASE_BUILDER_INSTANCES(declare, T)                                      \
  declare Matrix4<T> build_projection<T>(Family, Convention, int, const Pick&);         \
  declare Vector4<T> build_plane<T>(const Matrix4<T>&, Convention, Place, const Pick&); \
  declare Case<T> build_case<T>(Family, Convention, Place, int, const Pick&);           \
  declare Case<T> spoil<T>(Case<T>, Defect, const Pick&);                               \
  declare Vector4<T> unit_normal<T>(const Vector4<T>&);                                 \
  declare Case<T> choose_case<T>(const Contract&, bool, const Pick&);
#ifndef OBLIQUE_CHECKER_HEADER_ONLY
OBLIQUE_CASE_BUILDER_INSTANCES(extern template, float)
OBLIQUE_CASE_BUILDER_INSTANCES(extern template, double)
OBLIQUE_CASE_BUILDER_INSTANCES(extern template, long double)
#endif

}  // namespace OBLIQUE_EIGEN_LAYOUT
}  // namespace oblique::cases

// A file built with OBLIQUE_CHECKER_HEADER_ONLY compiles the builder with its own flags (its
// Eigen layout), as it does the checker and the generators.
#ifdef OBLIQUE_CHECKER_HEADER_ONLY
#include "oblique/cases/detail/case_builder_definitions.h"
#endif
