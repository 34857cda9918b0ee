// libFuzzer target: the core's references for the code around the matrix (depth reconstruction,
// culling planes, the pass camera and its plane, the kept region's vertices), computed in the
// scalar type the input's first byte picks, judged by the consumer properties through the fuzz
// driver (oblique::fuzzing::test_consumers). A finding is a reference that breaks its property or
// a bound too tight for careful arithmetic: either is a bug of ours.
#include "oblique/fuzzing.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const auto f = oblique::oracle::reference_consumers<float>();
  static const auto d = oblique::oracle::reference_consumers<double>();
  static const auto ld = oblique::oracle::reference_consumers<long double>();
  switch (size ? data[0] % 3 : 1) {
    case 0: return oblique::fuzzing::test_consumers(data, size, f);
    case 1: return oblique::fuzzing::test_consumers(data, size, d);
    default: return oblique::fuzzing::test_consumers(data, size, ld);
  }
}
