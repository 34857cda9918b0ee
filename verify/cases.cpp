#include "cases.h"

#include <algorithm>

#include "oblique/properties/judge.h"
#include "oblique/protocol/protocol.h"

namespace oblique::verify {

using generators::Defect;

template <class T>
std::string VerifyCase<T>::kind() const {
  return has_defect ? "no answer: " + std::string(generators::defect_name(defect))
                    : std::string(generators::place_name(c.place));
}

namespace {

/// A case of the resolved contract: four in five have an answer (the pick shrinks toward those),
/// the others one of its defects when its statuses are judged.
template <class T>
rc::Gen<VerifyCase<T>> verify_case(const Contract& contract) {
  const bool defects = *contract.statuses != properties::StatusContract::answers_only;
  return rc::gen::exec([contract, defects] {
    VerifyCase<T> v;
    if (!defects || *rc::gen::resize(100, rc::gen::inRange(0, 5)) < 4) {
      v.c = *generators::valid_case_for<T>(contract);
    } else {
      const generators::InvalidCase<T> ic = *generators::invalid_case_for<T>(contract);
      v.c = ic.base;
      v.has_defect = true;
      v.defect = ic.defect;
    }
    return v;
  });
}

template <class E>
bool contains(const std::vector<E>& list, E value) {
  return std::find(list.begin(), list.end(), value) != list.end();
}

}  // namespace

template <class T>
Draws<T>::Draws(const Contract& given)
    : contract_(resolved(given, {Convention::gl}, properties::StatusContract::any_refusal,
                         /*own_row3_accuracy=*/true)),
      generator_(verify_case<T>(contract_)) {
  const bool answers_only = *contract_.statuses == properties::StatusContract::answers_only;
  const bool unit = given.planes == Planes::unit;
  if (unit && !contains(contract_.places, generators::Place::scaled))
    notes_.push_back("place scaled (unit-normal planes)");
  if (answers_only)
    notes_.push_back("every input without an exact answer (statuses answers_only)");
  else if (!contract_.refusals.empty())
    notes_.push_back("inputs needing a refusal the contract does not list");
  for (generators::Place p : generators::all_places) {
    if (!contains(contract_.places, p) && !(unit && p == generators::Place::scaled))
      notes_.push_back("place " + std::string(generators::place_name(p)));
  }
  for (Defect d : generators::all_defects) {
    if (!answers_only && !contains(contract_.defects, d))
      notes_.push_back("no answer: " + std::string(generators::defect_name(d)));
  }
  checks_.row3_accuracy = *contract_.row3_accuracy;
  checks_.properties = contract_.properties;
  checks_.statuses = *contract_.statuses;
}

template <class T>
bool Draws<T>::needs_status() const {
  return !properties::has_every_refusal(*contract_.statuses, contract_.refusals);
}

template <class T>
std::string Draws<T>::left_out(const properties::FilteredProblem<T>& problem) const {
  return properties::not_judged(problem, checks_.statuses, contract_.refusals);
}

template <class T>
std::string request_text(const generators::Case<T>& c) {
  return protocol::request_line(c.matrix, c.plane, c.convention);
}

template <class T>
std::optional<Found<T>> judge(const properties::FilteredProblem<T>& problem,
                              const protocol::TypedAnswer<T>& answer,
                              const properties::Checks& checks) {
  const properties::Outcome<T> outcome{answer.status, answer.projection};
  const properties::Judgement judgement = properties::judge(problem, outcome, checks);
  const properties::Finding* violation = judgement.violation();
  if (!violation) return std::nullopt;
  Found<T> f;
  f.finding = *violation;
  if (answer.status == Status::ok) f.result = answer.projection;
  return f;
}

template <class T>
void Seen::count(const VerifyCase<T>& v) {
  ++families[std::string(generators::family_name(v.c.family))];
  ++conventions[std::string(convention_name(v.c.convention))];
  if (v.has_defect)
    ++defects[std::string(generators::defect_name(v.defect))];
  else
    ++places[std::string(generators::place_name(v.c.place))];
}

std::string Seen::summary(const std::map<std::string, long>& counts) {
  std::string out;
  for (const auto& [name, n] : counts)
    out += (out.empty() ? "" : ", ") + name + " " + std::to_string(n);
  return out.empty() ? "none" : out;
}

#define OBLIQUE_VERIFY_CASES(T)                                                    \
  template struct VerifyCase<T>;                                                   \
  template class Draws<T>;                                                         \
  template std::string request_text<T>(const generators::Case<T>&);                \
  template std::optional<Found<T>> judge<T>(const properties::FilteredProblem<T>&, \
                                            const protocol::TypedAnswer<T>&,       \
                                            const properties::Checks&);            \
  template void Seen::count<T>(const VerifyCase<T>&);
OBLIQUE_VERIFY_CASES(float)
OBLIQUE_VERIFY_CASES(double)
#undef OBLIQUE_VERIFY_CASES

}  // namespace oblique::verify
