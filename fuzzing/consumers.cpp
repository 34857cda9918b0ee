// oblique::fuzzing::test_consumers() (oblique/fuzzing.h): the code around the matrix on decoded
// cases, judged by the consumer properties; compiled once for float, double and long double.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "oblique/fuzzing.h"
#include "oblique/fuzzing/driver.h"
#include "oblique/mistakes/consumer_mistakes.h"
#include "oblique/oblique.h"

namespace oblique::fuzzing {

namespace {

/// Counts a finding; on a violation prints it with the inputs and aborts.
void settle(const std::string& consumer, const oracle::ConsumerFinding& finding,
            const std::string& inputs) {
  if (!finding.judged) {
    counts().left_out({}, finding.detail);
    return;
  }
  counts().judged({});
  if (finding.holds) return;
  std::fprintf(stderr, "oblique: %s violates %s\n%s", consumer.c_str(),
               oracle::describe(finding).c_str(), inputs.c_str());
  std::fflush(stderr);
  std::abort();
}

}  // namespace

inline namespace OBLIQUE_EIGEN_LAYOUT {

template <class T>
int test_consumers(const std::uint8_t* data, std::size_t size, const Consumers<T>& consumers,
                   const Contract& given) {
  const Contract contract =
      resolved(given, cases::every_convention(), cases::StatusContract::exact, false);
  // Built cases unspoiled: the code around the matrix is judged where the matrix has an answer.
  FuzzCase c = decode(data, size, contract, /*defects=*/false);
  if (describing()) describe(c);
  if (!in_contract(c, contract)) return 0;
  // The choices: the input read from its end, two bytes per pick.
  std::vector<std::uint8_t> tail(data, data + size);
  std::reverse(tail.begin(), tail.end());
  ByteReader choices(tail.data(), tail.size());
  auto pick = [&choices](int lo, int hi) {
    const unsigned v = choices.byte() | (unsigned(choices.byte()) << 8);
    return lo + static_cast<int>(v % static_cast<unsigned>(hi - lo));
  };
  Matrix4<T> m;
  Vector4<T> plane;
  for (int i = 0; i < 4; ++i) {
    plane(i) = narrow<T>(c.input.plane(i));
    for (int j = 0; j < 4; ++j) m(i, j) = narrow<T>(c.input.matrix(i, j));
  }
  oracle::consumer_round<T>(
      m, plane, c.input.convention, consumers, pick,
      [&consumers](const oracle::ConsumerFinding& finding, const std::string& inputs, bool) {
        settle(consumers.name, finding, inputs);
      },
      mistakes::explain_consumer<T>);
  return 0;
}

#define OBLIQUE_FUZZING_CONSUMERS(T)                                                    \
  template int test_consumers<T>(const std::uint8_t*, std::size_t, const Consumers<T>&, \
                                 const Contract&);
OBLIQUE_FUZZING_CONSUMERS(float)
OBLIQUE_FUZZING_CONSUMERS(double)
OBLIQUE_FUZZING_CONSUMERS(long double)
#undef OBLIQUE_FUZZING_CONSUMERS

}  // namespace OBLIQUE_EIGEN_LAYOUT
}  // namespace oblique::fuzzing
