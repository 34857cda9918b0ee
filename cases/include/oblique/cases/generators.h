// RapidCheck generators of cases: the one case builder (case_builder.h) fed RapidCheck's choices,
// so failures shrink, with RapidCheck's spread over families, conventions, places and defects:
// every family in every run, and every sign pattern of every family.
//
// RapidCheck's own double generator produces no zeros, subnormals or boundaries and shrinks
// doubles poorly; nothing here uses it.
#pragma once

#include <rapidcheck.h>

#include <iterator>
#include <ostream>
#include <vector>

#include "oblique/cases/case_builder.h"
#include "oblique/cases/case_kinds.h"
#include "oblique/cases/contract.h"
#include "oblique/oblique.h"
#include "oblique/protocol/numbers.h"
#include "oblique/references/depth_reconstruction.h"

namespace oblique::cases {

/// RapidCheck's pick in [lo, hi), inside rc::gen::exec: the builder's picks (case_builder.h,
/// consumer_cases.h) as RapidCheck choices, which shrink toward lo.
inline int rc_pick(int lo, int hi) {
  return *rc::gen::inRange(lo, hi);
}

namespace detail {

/// One of `all`, uniformly whatever RapidCheck's size (which otherwise favours the first),
/// shrinking toward the first.
template <class E>
rc::Gen<E> category(std::vector<E> all) {
  const std::size_t n = all.size();
  return rc::gen::map(rc::gen::resize(100, rc::gen::inRange<std::size_t>(0, n)),
                      [all = std::move(all)](std::size_t i) { return all[i]; });
}
/// One of `all` by the generation's size: size k gives all[k % n]. RapidCheck spreads a run's
/// sizes evenly over 0..max_size (100), so a run of 100 cases draws each of up to 11 choices 9
/// times or more, whatever the seed (a uniform pick of 11 misses one in about 1 run of 1,000,
/// and the suite runs dozens). The pick does not shrink.
template <class E>
rc::Gen<E> cycled(std::vector<E> all) {
  return rc::gen::withSize([all = std::move(all)](int size) {
    return rc::gen::just(all[static_cast<std::size_t>(size) % all.size()]);
  });
}

}  // namespace detail

/// A projection of `family` in `convention` (build_projection()); `round` as there, picked when
/// negative.
template <class T>
rc::Gen<Matrix4<T>> projection(Family family, Convention convention, int round = -1) {
  return rc::gen::exec(
      [=] { return build_projection<T>(family, convention, round, Pick(rc_pick)); });
}

/// A plane at `place` for the projection m (build_plane()).
template <class T>
rc::Gen<Vector4<T>> plane(const Matrix4<T>& m, Convention convention, Place place) {
  return rc::gen::exec([=] { return build_plane<T>(m, convention, place, Pick(rc_pick)); });
}

/// A valid-looking case of one of `families` in one of `conventions` at one of `places` (all
/// non-empty).
template <class T>
rc::Gen<Case<T>> valid_case_in(std::vector<Family> families, std::vector<Convention> conventions,
                               std::vector<Place> places = every_place()) {
  return rc::gen::exec([families, conventions, places] {
    const Family family = *detail::cycled(families);  // every family in every run, not by luck
    // The family's round in the run (the families cycle by size): its sign pattern, so every
    // pattern of every family is drawn in every run too.
    const int round = *rc::gen::withSize(
        [n = static_cast<int>(families.size())](int size) { return rc::gen::just(size / n); });
    const Convention convention = *detail::category(conventions);
    const Place place = *detail::category(places);
    return build_case<T>(family, convention, place, round, Pick(rc_pick));
  });
}

/// A valid-looking case of one family (for the properties that apply to one family only).
template <class T>
rc::Gen<Case<T>> valid_case_of(Family family) {
  return valid_case_in<T>({family}, every_convention());
}

/// A valid-looking case of any family, convention and hard place (the picks cover all of them).
template <class T>
rc::Gen<Case<T>> valid_case() {
  return valid_case_in<T>(every_family(), every_convention());
}

/// An input that has no answer, or sits next to one that has none: a valid case of the lists
/// spoiled by one of `defects` (the case's defect).
template <class T>
rc::Gen<Case<T>> invalid_case_in(std::vector<Family> families, std::vector<Convention> conventions,
                                 std::vector<Place> places = every_place(),
                                 std::vector<Defect> defects = std::vector<Defect>(
                                     std::begin(all_defects), std::end(all_defects))) {
  return rc::gen::exec([families, conventions, places, defects] {
    const Defect defect = *detail::category(defects);
    return spoil<T>(*valid_case_in<T>(families, conventions, places), defect, Pick(rc_pick));
  });
}

/// An input of any family and convention that has no answer, or sits next to one that has none.
template <class T>
rc::Gen<Case<T>> invalid_case() {
  return invalid_case_in<T>(every_family(), every_convention());
}

/// A valid-looking case of a resolved contract (oblique::resolved()): its families, conventions
/// and places, the plane scaled to a unit normal when its planes are unit.
template <class T>
rc::Gen<Case<T>> valid_case_for(const Contract& contract) {
  return rc::gen::map(valid_case_in<T>(contract.families, contract.conventions, contract.places),
                      [unit = contract.planes == Planes::unit](Case<T> c) {
                        if (unit) c.plane = unit_normal(c.plane);
                        return c;
                      });
}

/// An input without an answer (or next to one) of a resolved contract: one of its defects on a
/// case of valid_case_for().
template <class T>
rc::Gen<Case<T>> invalid_case_for(const Contract& contract) {
  return rc::gen::map(invalid_case_in<T>(contract.families, contract.conventions, contract.places,
                                         contract.defects),
                      [unit = contract.planes == Planes::unit](Case<T> c) {
                        if (unit) c.plane = unit_normal(c.plane);
                        return c;
                      });
}

/// The generators oblique::generators compiles (cases/generators.cpp), for T = float, double
/// and long double: `declare` is `template` there and `extern template` in a program that links
/// them (OBLIQUE_LINKED_GENERATORS, which the oblique::generators target sets).
#define OBLIQUE_GENERATOR_INSTANCES(declare, T)                                             \
  declare rc::Gen<Matrix4<T>> projection<T>(Family, Convention, int);                       \
  declare rc::Gen<Vector4<T>> plane<T>(const Matrix4<T>&, Convention, Place);               \
  declare rc::Gen<Case<T>> valid_case_in<T>(std::vector<Family>, std::vector<Convention>,   \
                                            std::vector<Place>);                            \
  declare rc::Gen<Case<T>> valid_case_of<T>(Family);                                        \
  declare rc::Gen<Case<T>> valid_case<T>();                                                 \
  declare rc::Gen<Case<T>> invalid_case_in<T>(std::vector<Family>, std::vector<Convention>, \
                                              std::vector<Place>, std::vector<Defect>);     \
  declare rc::Gen<Case<T>> invalid_case<T>();                                               \
  declare rc::Gen<Case<T>> valid_case_for<T>(const Contract&);                              \
  declare rc::Gen<Case<T>> invalid_case_for<T>(const Contract&);

#if defined(OBLIQUE_LINKED_GENERATORS) && !defined(OBLIQUE_CHECKER_HEADER_ONLY)
OBLIQUE_GENERATOR_INSTANCES(extern template, float)
OBLIQUE_GENERATOR_INSTANCES(extern template, double)
OBLIQUE_GENERATOR_INSTANCES(extern template, long double)
#endif

}  // namespace oblique::cases

namespace oblique::cases {

/// How RapidCheck shows a case: every number so that it reads back to the same value.
template <class T>
void showValue(const Case<T>& c, std::ostream& os) {
  if (c.defect) os << defect_name(*c.defect) << ": ";
  os << family_name(c.family) << " " << convention_name(c.convention) << " " << place_name(c.place)
     << "\nM = [";
  for (int i = 0; i < 16; ++i)
    os << (i ? (i % 4 ? ", " : "; ") : "") << protocol::format_number(c.matrix(i / 4, i % 4));
  os << "]\nC = (";
  for (int i = 0; i < 4; ++i) os << (i ? ", " : "") << protocol::format_number(c.plane(i));
  os << ")";
}

inline void showValue(Family f, std::ostream& os) {
  os << family_name(f);
}
inline void showValue(Place p, std::ostream& os) {
  os << place_name(p);
}
inline void showValue(Defect d, std::ostream& os) {
  os << defect_name(d);
}

}  // namespace oblique::cases

namespace oblique {

inline void showValue(Convention c, std::ostream& os) {
  os << convention_name(c);
}
inline void showValue(DepthBuffer b, std::ostream& os) {
  os << depth_buffer_name(b);
}

}  // namespace oblique
