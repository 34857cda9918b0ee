// libFuzzer target: the core (or the implementations OBLIQUE_IMPL names) on decoded projections
// and planes, through the fuzz driver's parts (oblique/fuzzing/driver.h), one case judged for
// several implementations. Aborts, naming the property, when an answer breaks the status
// contract, a property, or (for the core) row 3's accuracy bound and its ulps promise. An unknown
// OBLIQUE_IMPL name is an error (exit 2), never a silent pass.
#include <cstdio>
#include <cstdlib>

#include "oblique/fuzzing/driver.h"

namespace {

template <class T>
void check_all(const oblique::fuzzing::FuzzCase& c) {
  static const auto implementations = oblique::mistakes::selected_implementations<T>();
  // One problem for the case, one judgement per distinct answer (the core's methods mostly agree).
  oblique::fuzzing::CaseJudge<T> judge(c);
  for (const auto& impl : implementations) {
    const bool core = impl.name.rfind("core_", 0) == 0;
    oblique::fuzzing::check<T>(c, judge, impl, impl.checks(core));
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool selection_checked = [] {
    const std::string error = oblique::mistakes::implementation_selection_error();
    if (!error.empty()) {
      std::fprintf(stderr, "%s\n", error.c_str());
      std::exit(2);
    }
    return true;
  }();
  (void)selection_checked;
  const oblique::fuzzing::FuzzCase c = oblique::fuzzing::decode(data, size);
  if (oblique::fuzzing::describing()) oblique::fuzzing::describe(c);
  switch (c.scalar) {
    case oblique::protocol::Precision::float32: check_all<float>(c); break;
    case oblique::protocol::Precision::float64: check_all<double>(c); break;
    case oblique::protocol::Precision::long_double: check_all<long double>(c); break;
  }
  return 0;
}
