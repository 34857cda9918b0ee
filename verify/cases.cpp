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

template <class T>
void Seen::count(const cases::Case<T>& v) {
  ++families[std::string(cases::family_name(v.family))];
  ++conventions[std::string(convention_name(v.convention))];
  if (v.defect)
    ++defects[std::string(cases::defect_name(*v.defect))];
  else
    ++places[std::string(cases::place_name(v.place))];
}

std::string Seen::summary(const std::map<std::string, long>& counts) {
  return counts_text(counts);
}

template <class T>
void LeftOut::count(const cases::Case<T>& v, const std::string& reason, bool unclaimed) {
  ++why[reason];
  const std::string family(cases::family_name(v.family)), convention(convention_name(v.convention));
  ++families[family];
  ++conventions[convention];
  if (unclaimed) {
    ++unclaimed_families[family];
    ++unclaimed_conventions[convention];
  }
}

namespace {

long count_of(const std::map<std::string, long>& counts, const std::string& key) {
  const auto it = counts.find(key);
  return it == counts.end() ? 0 : it->second;
}

/// The contract's families and conventions by name, each with its judged and left-out counts.
struct Claim {
  std::string what, name;
  long judged, left;
  long unclaimed;  ///< of `left`, inputs the contract does not claim
};

std::vector<Claim> claims(const Contract& contract, const Seen& seen, const LeftOut& left_out) {
  std::vector<Claim> out;
  for (cases::Family f : contract.families) {
    const std::string name(cases::family_name(f));
    out.push_back({"family", name, count_of(seen.families, name), count_of(left_out.families, name),
                   count_of(left_out.unclaimed_families, name)});
  }
  for (Convention c : contract.conventions) {
    const std::string name(convention_name(c));
    out.push_back({"convention", name, count_of(seen.conventions, name),
                   count_of(left_out.conventions, name),
                   count_of(left_out.unclaimed_conventions, name)});
  }
  return out;
}

}  // namespace

std::vector<std::string> unjudged_claims(const Contract& contract, const Seen& seen,
                                         const LeftOut& left_out, long done) {
  std::vector<std::string> out;
  for (const Claim& c : claims(contract, seen, left_out)) {
    if (c.judged > 0) continue;
    std::string line =
        "the contract claims " + c.what + " " + c.name + ", and no case of it was judged: ";
    if (c.left == 0) {
      line += "none was drawn in " + std::to_string(done) +
              " cases: raise --cases or --time-limit, or leave " + c.name + " out of the contract";
    } else {
      line += "all " + std::to_string(c.left) +
              " drawn were left out by the contract (why, over the run: " +
              Seen::summary(left_out.why) +
              "): list the statuses those inputs get (\"statuses\", \"refusals\"), or leave " +
              c.name + " out of the contract";
    }
    out.push_back(std::move(line));
  }
  return out;
}

std::string partly_judged(const Contract& contract, const Seen& seen, const LeftOut& left_out,
                          double share) {
  std::string out;
  for (const Claim& c : claims(contract, seen, left_out)) {
    const long left = c.left - c.unclaimed;  // of what the contract claims
    if (c.judged == 0 || !left_out_beyond(left, c.judged + left, share)) continue;
    out += (out.empty() ? "" : ", ") + c.what + " " + c.name + " " + std::to_string(left) + " of " +
           std::to_string(c.judged + left);
  }
  return out;
}

#define OBLIQUE_VERIFY_CASES(T)                                                             \
  template class Draws<T>;                                                                  \
  template std::string request_text<T>(const cases::Case<T>&);                              \
  template std::optional<Found<T>> judge_answer<T>(const oracle::FilteredProblem<T>&,       \
                                                   const Answer<T>&, const cases::Checks&); \
  template bool consistent_with_float<T>(const cases::Case<T>&, const Matrix4<T>&,          \
                                         const cases::Checks&);                             \
  template void Seen::count<T>(const cases::Case<T>&);                                      \
  template void LeftOut::count<T>(const cases::Case<T>&, const std::string&, bool);
OBLIQUE_VERIFY_CASES(float)
OBLIQUE_VERIFY_CASES(double)
#undef OBLIQUE_VERIFY_CASES

}  // namespace oblique::verify
