// oblique::properties: Checker (oblique/oracle/checker.h) over the filtered checker, compiled
// once for float, double and long double.
#include "oblique/oracle/checker.h"

#include "oblique/oracle/filtered.h"
#include "oblique/oracle/judge.h"

namespace oblique::oracle {

template <class T>
Checker<T>::Checker(const Matrix4<T>& m, const Vector4<T>& c, Convention convention)
    : problem_(std::make_unique<FilteredProblem<T>>(m, c, convention)) {}

template <class T>
Checker<T>::~Checker() = default;
template <class T>
Checker<T>::Checker(Checker&&) noexcept = default;
template <class T>
Checker<T>& Checker<T>::operator=(Checker&&) noexcept = default;

template <class T>
Status Checker<T>::exact_status() const {
  return problem_->exact_status();
}

template <class T>
std::vector<Status> Checker<T>::acceptable_statuses() const {
  return problem_->acceptable_statuses();
}

template <class T>
std::string Checker<T>::not_judged(StatusContract contract,
                                   const std::vector<Status>& refusals) const {
  return oracle::not_judged(*problem_, contract, refusals);
}

template <class T>
Judgement Checker<T>::judge(const Answer<T>& outcome, const Checks& checks) const {
  return oracle::judge(*problem_, outcome, checks);
}

template class Checker<float>;
template class Checker<double>;
template class Checker<long double>;

}  // namespace oblique::oracle
