// For test executables compiled for more than the baseline instruction set (tests/CMakeLists.txt:
// the accuracy tests under -O3 -march=native and -mavx2 -mfma -ffp-contract=fast): before any
// other code of the executable runs, checks that this processor has the instructions the build
// targets (the compiler's __AVX__, __AVX2__, __FMA__, ... macros), and where it does not, says
// which are missing and exits with 77, which CTest reports as a skip (SKIP_RETURN_CODE). This
// function itself is compiled without them, so it runs on any x86-64 processor.
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace {

#if defined(__x86_64__) && defined(__GNUC__)
__attribute__((constructor(101), target("no-avx,no-sse4.2"))) void require_targeted_instructions() {
  __builtin_cpu_init();    // before __builtin_cpu_supports in a constructor
  char missing[128] = "";  // no std::string: its out-of-line code is compiled for the target
#define OBLIQUE_REQUIRE(feature) \
  if (!__builtin_cpu_supports(feature)) std::strcat(missing, " " feature);
#if defined(__SSE4_2__)
  OBLIQUE_REQUIRE("sse4.2")
#endif
#if defined(__AVX__)
  OBLIQUE_REQUIRE("avx")
#endif
#if defined(__AVX2__)
  OBLIQUE_REQUIRE("avx2")
#endif
#if defined(__FMA__)
  OBLIQUE_REQUIRE("fma")
#endif
#if defined(__BMI2__)
  OBLIQUE_REQUIRE("bmi2")
#endif
#if defined(__AVX512F__)
  OBLIQUE_REQUIRE("avx512f")
#endif
#if defined(__AVX512VL__)
  OBLIQUE_REQUIRE("avx512vl")
#endif
#if defined(__AVX512BW__)
  OBLIQUE_REQUIRE("avx512bw")
#endif
#if defined(__AVX512DQ__)
  OBLIQUE_REQUIRE("avx512dq")
#endif
#undef OBLIQUE_REQUIRE
  if (missing[0] != 0) {
    std::fprintf(stderr, "skipped: the processor lacks instructions this build targets:%s\n",
                 missing);
    std::_Exit(77);
  }
}
#endif

}  // namespace
