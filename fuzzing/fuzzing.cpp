// oblique::fuzzing: test_one_input() (oblique/fuzzing.h) over the driver's decoder and the case's
// judge (oblique/fuzzing/driver.h), compiled once for float, double and long double.
#include "oblique/fuzzing.h"

#include "oblique/fuzzing/driver.h"

namespace oblique::fuzzing {
inline namespace OBLIQUE_EIGEN_LAYOUT {

template <class T>
int test_one_input(const std::uint8_t* data, std::size_t size,
                   const oracle::Implementation<T>& impl, const Contract& given) {
  const Contract contract = resolved(given, impl.conventions, impl.status_contract(), false);
  // Built cases spoiled by the contract's defects where inputs without an answer are judged.
  FuzzCase c =
      decode(data, size, contract, *contract.statuses != cases::StatusContract::answers_only);
  if (describing()) describe(c);
  if (!in_contract(c, contract)) return 0;
  cases::Checks checks = impl.checks(*contract.row3_accuracy);
  checks.statuses = *contract.statuses;
  checks.properties = contract.properties;
  // As in the property suite: a function without statuses is judged where an answer exists and
  // the input is decidable in T (oracle::not_judged()).
  CaseJudge<T> judge(c);
  check<T>(c, judge, impl, checks, checks.statuses != cases::StatusContract::answers_only,
           contract.refusals, contract.defects);
  return 0;
}

#define OBLIQUE_FUZZING_INSTANCE(T)                                \
  template int test_one_input<T>(const std::uint8_t*, std::size_t, \
                                 const oracle::Implementation<T>&, const Contract&);
OBLIQUE_FUZZING_INSTANCE(float)
OBLIQUE_FUZZING_INSTANCE(double)
OBLIQUE_FUZZING_INSTANCE(long double)
#undef OBLIQUE_FUZZING_INSTANCE

}  // namespace OBLIQUE_EIGEN_LAYOUT
}  // namespace oblique::fuzzing
