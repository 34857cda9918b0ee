#include "cases.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <type_traits>

#include "oblique/oracle/judge.h"
#include "oblique/protocol/protocol.h"

namespace oblique::verify {

using cases::Defect;

namespace {

/// A case of the resolved contract: four in five have an answer (the pick shrinks toward those),
/// the others one of its defects when its statuses are judged.
template <class T>
rc::Gen<cases::Case<T>> verify_case(const Contract& contract) {
  const bool defects = *contract.statuses != cases::StatusContract::answers_only;
  return rc::gen::exec([contract, defects] {
    if (!defects || *rc::gen::resize(100, rc::gen::inRange(0, 5)) < 4)
      return *cases::valid_case_for<T>(contract);
    return *cases::invalid_case_for<T>(contract);
  });
}

template <class E>
bool contains(const std::vector<E>& list, E value) {
  return std::find(list.begin(), list.end(), value) != list.end();
}

}  // namespace

template <class T>
Draws<T>::Draws(const Contract& given)
    : contract_(resolved(given, {Convention::gl}, cases::StatusContract::any_refusal,
                         /*own_row3_accuracy=*/true)),
      generator_(verify_case<T>(contract_)) {
  const bool answers_only = *contract_.statuses == cases::StatusContract::answers_only;
  const bool unit = given.planes == Planes::unit;
  if (unit && !contains(contract_.places, cases::Place::scaled))
    notes_.push_back("place scaled (unit-normal planes)");
  if (answers_only)
    notes_.push_back("every input without an exact answer (statuses answers_only)");
  else if (!contract_.refusals.empty())
    notes_.push_back("inputs needing a refusal the contract does not list");
  for (cases::Place p : cases::all_places) {
    if (!contains(contract_.places, p) && !(unit && p == cases::Place::scaled))
      notes_.push_back("place " + std::string(cases::place_name(p)));
  }
  for (Defect d : cases::all_defects) {
    if (!answers_only && !contains(contract_.defects, d))
      notes_.push_back("no answer: " + std::string(cases::defect_name(d)));
  }
  checks_.row3_accuracy = *contract_.row3_accuracy;
  checks_.properties = contract_.properties;
  checks_.statuses = *contract_.statuses;
}

template <class T>
bool Draws<T>::needs_status() const {
  return !oracle::has_every_refusal(*contract_.statuses, contract_.refusals);
}

template <class T>
std::string Draws<T>::left_out(const oracle::FilteredProblem<T>& problem) const {
  return oracle::not_judged(problem, checks_.statuses, contract_.refusals);
}

template <class T>
std::string request_text(const cases::Case<T>& c) {
  return protocol::request_line(c.matrix, c.plane, c.convention);
}

template <class T>
std::optional<Found<T>> judge_answer(const oracle::FilteredProblem<T>& problem,
                                     const Answer<T>& answer, const cases::Checks& checks) {
  const oracle::Judgement judgement = oracle::judge(problem, answer, checks);
  const oracle::Finding* violation = judgement.violation();
  if (!violation) return std::nullopt;
  Found<T> f;
  f.finding = *violation;
  if (answer.status == Status::ok) f.result = answer.projection;
  return f;
}

template <class T>
bool consistent_with_float(const cases::Case<T>& c, const Matrix4<T>& answer,
                           const cases::Checks& checks) {
  if constexpr (std::is_same_v<T, float>) {
    return false;
  } else {
    const Matrix4<float> answer_f = answer.template cast<float>();
    if (!answer_f.allFinite()) return false;
    for (int i = 0; i < 16; ++i) {
      const T x = answer(i / 4, i % 4);
      if (static_cast<T>(answer_f(i / 4, i % 4)) == x) continue;
      char nine[40];
      std::snprintf(nine, sizeof nine, "%.9Lg", static_cast<long double>(x));
      if (static_cast<T>(std::strtold(nine, nullptr)) != x) return false;
    }
    const Matrix4<float> m = c.matrix.template cast<float>();
    const Vector4<float> plane = c.plane.template cast<float>();
    if (!m.allFinite() || !plane.allFinite()) return false;
    const oracle::FilteredProblem<float> problem(m, plane, c.convention);
    const Answer<float> outcome{Status::ok, answer_f};
    return oracle::judge(problem, outcome, checks).violation() == nullptr;
  }
}

run::Advice matrix_advice() {
  run::Advice advice;
  advice.judge_left_out = "list the statuses those inputs get (\"statuses\", \"refusals\")";
  return advice;
}

#define OBLIQUE_VERIFY_CASES(T)                                                             \
  template class Draws<T>;                                                                  \
  template std::string request_text<T>(const cases::Case<T>&);                              \
  template std::optional<Found<T>> judge_answer<T>(const oracle::FilteredProblem<T>&,       \
                                                   const Answer<T>&, const cases::Checks&); \
  template bool consistent_with_float<T>(const cases::Case<T>&, const Matrix4<T>&,          \
                                         const cases::Checks&);
OBLIQUE_VERIFY_CASES(float)
OBLIQUE_VERIFY_CASES(double)
#undef OBLIQUE_VERIFY_CASES

}  // namespace oblique::verify
