// The error-free transformations and double-word operations of error_free.h against exact
// rational arithmetic (GMP): every claim the header makes, for float, double and long double, on
// deterministic pseudo-random inputs (wide exponent ranges, both signs, zeros, significands next
// to powers of two, cancellation) and on hand-made edge cases. The oracle is the exact value and
// its correct rounding (oracle::exact::round_to), never a recorded number.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "oblique/numeric/error_free.h"
#include "oblique/oracle/exact.h"

namespace oblique::eft {
namespace {

using oracle::exact::Rational;

template <class T>
constexpr int kDigits = std::numeric_limits<T>::digits;
template <class T>
constexpr int kMinExponent = std::numeric_limits<T>::min_exponent;  // normals are >= 2^(min - 1)
template <class T>
constexpr int kMaxExponent = std::numeric_limits<T>::max_exponent;  // finite values are < 2^max
/// The smallest exponent of a (subnormal) value: 2^(min - p) is the smallest positive one.
template <class T>
constexpr int kLowestExponent = kMinExponent<T> - kDigits<T>;
/// log2 of two_prod's threshold for falling back on std::fma (as documented: 2^(p/2 + 2) below
/// overflow, with p/2 rounded up as split() rounds it).
template <class T>
constexpr int kFallbackExponent = kMaxExponent<T> - (kDigits<T> + 1) / 2 - 2;

template <class T>
Rational rational(T x) {
  return oracle::exact::to_rational(x);
}
template <class T>
Rational rational(Pair<T> x) {
  return oracle::exact::to_rational(x.hi) + oracle::exact::to_rational(x.lo);
}
template <class T>
bool finite(Pair<T> x) {
  return std::isfinite(x.hi) && std::isfinite(x.lo);
}

/// u = eps / 2 = 2^-p, the unit roundoff.
template <class T>
Rational unit_roundoff() {
  return oracle::exact::power_of_two(-kDigits<T>);
}
/// gamma_n = n u / (1 - n u).
template <class T>
Rational gamma(long n) {
  const Rational nu = Rational(n) * unit_roundoff<T>();
  return nu / (1 - nu);
}

/// The number of significant bits of a dyadic rational (0 for 0).
int significant_bits(const Rational& x) {
  const mpz_class& num = x.get_num();
  if (num == 0) return 0;
  const mpz_class magnitude = abs(num);
  return static_cast<int>(mpz_sizeinbase(magnitude.get_mpz_t(), 2) -
                          mpz_scan1(magnitude.get_mpz_t(), 0));
}

/// The spacing of T at x: the quantum of |x|'s binade, or the subnormal quantum below them.
template <class T>
T ulp(T x) {
  const int e = x == T(0) ? kMinExponent<T> - 1 : std::max(std::ilogb(x), kMinExponent<T> - 1);
  return std::ldexp(T(1), e - kDigits<T> + 1);
}

template <class T>
std::string hex(T x) {
  std::ostringstream out;
  out << std::hexfloat << x;
  return out.str();
}
template <class T>
std::string hex(Pair<T> x) {
  return "{" + hex(x.hi) + ", " + hex(x.lo) + "}";
}
std::string decimal(const Rational& x) {
  std::ostringstream out;
  out << x.get_d();
  return out.str();
}

template <class T>
const char* type_name() {
  if (std::is_same_v<T, float>) return "float";
  return std::is_same_v<T, double> ? "double" : "long double";
}

/// Counts the cases of a check and its failures, keeping the first few failing inputs.
class Tally {
 public:
  explicit Tally(std::string what) : what_(std::move(what)) {}
  template <class Describe>
  void check(bool ok, Describe describe) {
    ++cases_;
    if (ok) return;
    if (failures_++ < 4) examples_ += "\n  " + describe();
  }
  int cases() const { return cases_; }
  /// Fails the test if any case failed, showing the first failing inputs.
  void expect_no_failure() const {
    EXPECT_EQ(failures_, 0) << what_ << ": " << failures_ << " of " << cases_ << " cases fail"
                            << examples_;
  }

 private:
  std::string what_;
  std::string examples_;
  int cases_ = 0;
  int failures_ = 0;
};

/// Pseudo-random values of T (fixed seeds: every run sees the same inputs).
template <class T>
class Generator {
 public:
  explicit Generator(std::uint64_t seed) : random_(seed) {}

  int integer(int low, int high) { return std::uniform_int_distribution<int>(low, high)(random_); }
  bool coin() { return (random_() & 1) != 0; }
  bool one_in(int n) { return random_() % static_cast<std::uint64_t>(n) == 0; }

  /// A significand in [1, 2) with p bits: uniform random bits, or one just above 1, just below
  /// 2, or with only a few leading bits set (1 itself among them).
  T significand() {
    constexpr int p = kDigits<T>;
    const std::uint64_t top = std::uint64_t{1} << (p - 1);
    const std::uint64_t below = top - 1;  // the p - 1 bits under the leading one
    std::uint64_t m = 0;
    switch (random_() % 8) {
      case 0: m = top + random_() % 4; break;
      case 1: m = top + below - random_() % 4; break;
      case 2: m = top | (random_() & below & ~(below >> integer(0, 6))); break;
      default: m = top | (random_() & below); break;
    }
    return std::ldexp(static_cast<T>(m), 1 - p);  // m < 2^p is exact in T
  }
  /// +-significand * 2^e (rounded by ldexp below the normal range).
  T at(int e) {
    const T x = std::ldexp(significand(), e);
    return coin() ? -x : x;
  }
  /// +-significand * 2^e with e uniform in [low, high].
  T value(int low, int high) { return at(integer(low, high)); }
  /// A fraction of magnitude in [2^-p, 1) (mostly near 1), or 0 one time in 16.
  T fraction() {
    if (one_in(16)) return T(0);
    return one_in(4) ? value(-kDigits<T>, -1) : value(-4, -1);
  }
  /// A normalized pair: hi with its exponent in [low, high], lo a random fraction of hi's ulp
  /// (fl(hi + lo) = hi).
  Pair<T> pair(int low, int high) {
    const T hi = value(low, high);
    T lo = fraction() * ulp(hi) / T(2);
    while (hi + lo != hi) lo /= T(2);  // below a power of two the spacing halves
    return {hi, lo};
  }

  template <class Vector>
  void shuffle(Vector& v) {
    std::shuffle(v.begin(), v.end(), random_);
  }

 private:
  std::mt19937_64 random_;
};

/// Summands for two_sum: independent exponents over the whole finite range (subnormals
/// included, sums below overflow), close exponents, near and exact cancellation, a b below half
/// an ulp of a, zeros.
template <class T>
std::pair<T, T> random_summands(Generator<T>& g) {
  constexpr int low = kLowestExponent<T>, high = kMaxExponent<T> - 2;
  const T a = g.value(low, high);
  T b = T(0);
  switch (g.integer(0, 5)) {
    case 0: b = g.value(low, high); break;
    case 1: b = g.at(std::clamp(std::ilogb(a) + g.integer(-kDigits<T> - 3, 3), low, high)); break;
    case 2:
      b = -a;
      for (int i = g.integer(0, 3); i > 0; --i) {
        b = std::nextafter(
            b, g.coin() ? std::numeric_limits<T>::infinity() : -std::numeric_limits<T>::infinity());
      }
      break;
    case 3: b = g.at(std::max(std::ilogb(a) - kDigits<T> - g.integer(0, 2), low)); break;
    case 4: b = g.coin() ? T(0) : -T(0); break;
    default: b = g.value(std::max(std::ilogb(a) - 8, low), std::min(std::ilogb(a) + 8, high));
  }
  return g.coin() ? std::pair<T, T>{a, b} : std::pair<T, T>{b, a};
}

/// Hand-made summands: zeros, ties at 1 and at powers of two, the extremes of the range.
template <class T>
std::vector<std::pair<T, T>> edge_summands() {
  constexpr int p = kDigits<T>;
  const T max = std::numeric_limits<T>::max(), tiny = std::numeric_limits<T>::denorm_min();
  const T smallest_normal = std::numeric_limits<T>::min();
  const T half_ulp = std::ldexp(T(1), -p);
  return {{T(0), T(0)},
          {-T(0), T(0)},
          {-T(0), -T(0)},
          {T(1), half_ulp},
          {T(1), -half_ulp},
          {T(1), -half_ulp / 2},
          {T(1) + 2 * half_ulp, half_ulp},
          {T(1), half_ulp * (1 + 2 * half_ulp)},
          {T(1), -T(1)},
          {T(1), -(T(1) - half_ulp)},
          {max / 2, max / 2},
          {max, -max},
          {max, -ulp(max)},
          {-max, half_ulp},
          {tiny, -tiny},
          {tiny, tiny},
          {smallest_normal, -tiny},
          {smallest_normal - tiny, tiny},
          {std::ldexp(T(1), kMaxExponent<T> - 2), std::ldexp(T(1), kLowestExponent<T>)},
          {T(3), std::ldexp(T(1), -2 * p)}};
}

#if defined(OBLIQUE_CONTRACTED_BUILD)
// error_free_contracted_test: this file compiled with -mfma -ffp-contract=fast (tests/
// CMakeLists.txt), as a user's -march=native build may compile the core. Its arithmetic runs FMA
// instructions, so on a processor without them every test skips, and says so.
class ProcessorHasFma : public ::testing::Environment {
 public:
  void SetUp() override {
    if (!__builtin_cpu_supports("fma")) {
      GTEST_SKIP() << "the processor has no FMA: the contracted build cannot run here";
    }
  }
};
::testing::Environment* const kProcessorHasFma =
    ::testing::AddGlobalTestEnvironment(new ProcessorHasFma);

/// a b + c as written, in a function of its own.
__attribute__((noinline)) double product_plus(double a, double b, double c) {
  return a * b + c;
}

// The other tests only mean something if this build does contract: (1 + 2^-30)(1 - 2^-30) - 1
// is -2^-60 fused, and 0 when the product is rounded first.
TEST(ContractedBuild, theCompilerFusesAProductAndASumIntoAnFma) {
  volatile double a = 1 + std::ldexp(1.0, -30), b = 1 - std::ldexp(1.0, -30), c = -1;
  EXPECT_EQ(product_plus(a, b, c), -std::ldexp(1.0, -60));
}
#endif

template <class T>
class ErrorFree : public ::testing::Test {};
using Scalars = ::testing::Types<float, double, long double>;
TYPED_TEST_SUITE(ErrorFree, Scalars);

constexpr int kRandomCases = 4000;

/// Checks that `sum(a, b)` (two_sum or fast_two_sum) is exact with its high word the rounded sum,
/// on the edge cases and random summands (the larger first where `larger_first`, as
/// fast_two_sum requires; both orders otherwise).
template <class T, class Sum>
void check_error_free_sum(const char* name, std::uint64_t seed, bool larger_first, Sum sum) {
  Generator<T> g(seed);
  Tally tally(name);
  const auto check = [&](T a, T b) {
    if (larger_first && std::fabs(a) < std::fabs(b)) std::swap(a, b);
    const Pair<T> s = sum(a, b);
    const Rational exact_sum = rational(a) + rational(b);
    tally.check(
        finite(s) && rational(s) == exact_sum && s.hi == oracle::exact::round_to<T>(exact_sum),
        [&] { return std::string(name) + "(" + hex(a) + ", " + hex(b) + ") = " + hex(s); });
  };
  for (const auto& [a, b] : edge_summands<T>()) {
    check(a, b);
    if (!larger_first) check(b, a);
    check(-a, -b);
  }
  for (int i = 0; i < kRandomCases; ++i) {
    const auto [a, b] = random_summands(g);
    check(a, b);
  }
  tally.expect_no_failure();
}

TYPED_TEST(ErrorFree, twoSumIsExactAndItsHighWordIsTheRoundedSum) {
  using T = TypeParam;
  check_error_free_sum<T>("two_sum", 0xe0f1, false, [](T a, T b) { return two_sum(a, b); });
}

TYPED_TEST(ErrorFree, fastTwoSumIsExactWhenTheFirstSummandIsTheLarger) {
  using T = TypeParam;
  check_error_free_sum<T>("fast_two_sum", 0xe0f2, true,
                          [](T a, T b) { return fast_two_sum(a, b); });
}

/// Checks that two_prod(a, b) is exact with its high word the rounded product.
template <class T>
void check_two_prod(Tally& tally, T a, T b) {
  const Pair<T> p = two_prod(a, b);
  const Rational product = rational(a) * rational(b);
  tally.check(finite(p) && rational(p) == product && p.hi == oracle::exact::round_to<T>(product),
              [&] { return "two_prod(" + hex(a) + ", " + hex(b) + ") = " + hex(p); });
}

/// The product's exponent from which two_prod is required to be exact: the product's last bit,
/// at 2^(2 - 2p) of it, is then well above the subnormal quantum 2^(min - p). (Measured: exact
/// products are lost from 2^(min + p - 3) down, where that bit falls below the quantum.)
template <class T>
constexpr int kWellAboveUnderflow = kMinExponent<T> + kDigits<T> + 4;

TYPED_TEST(ErrorFree, twoProdIsExactWellAboveUnderflow) {
  using T = TypeParam;
  Generator<T> g(0xe0f3);
  Tally tally("two_prod");
  constexpr int p = kDigits<T>;
  const T half_ulp = std::ldexp(T(1), -p);
  const std::vector<std::pair<T, T>> edges = {
      {T(0), T(0)},
      {T(1), T(1)},
      {T(1) + 2 * half_ulp, T(1) + 2 * half_ulp},
      {T(1) - half_ulp, T(1) - half_ulp},
      {T(1) + 2 * half_ulp, T(1) - half_ulp},
      {T(3), T(1) / T(3)},
      {std::ldexp(T(1), kWellAboveUnderflow<T> / 2), std::ldexp(T(1), kWellAboveUnderflow<T> / 2)},
      {std::ldexp(T(1) - half_ulp, kWellAboveUnderflow<T> / 2),
       std::ldexp(T(1) - half_ulp, kWellAboveUnderflow<T> / 2)},
      {std::numeric_limits<T>::denorm_min(), std::ldexp(T(1), kMaxExponent<T> - 1)},
      // Either side of the fallback threshold, the product a factor 2 to 3 below overflow.
      {std::nextafter(std::ldexp(T(1), kFallbackExponent<T>), T(0)),
       std::ldexp(T(1.5), kMaxExponent<T> - kFallbackExponent<T> - 2)},
      {std::ldexp(T(1), kFallbackExponent<T>),
       std::ldexp(T(1.5), kMaxExponent<T> - kFallbackExponent<T> - 2)},
      {std::numeric_limits<T>::max(), T(1) - half_ulp},
      {std::numeric_limits<T>::max(), std::ldexp(T(1), kMinExponent<T> + 2 * p)},
  };
  for (const auto& [a, b] : edges) {
    check_two_prod(tally, a, b);
    check_two_prod(tally, b, -a);
  }
  // Products from well above underflow to a factor 4 below overflow, operands anywhere
  // (subnormal or past the fallback threshold among them).
  for (int i = 0; i < kRandomCases; ++i) {
    const int product = g.integer(kWellAboveUnderflow<T>, kMaxExponent<T> - 3);
    const int ea = g.integer(std::max(kLowestExponent<T>, product - kMaxExponent<T> + 1),
                             std::min(kMaxExponent<T> - 1, product - kLowestExponent<T>));
    const T a = g.at(ea), b = g.at(product - ea);
    if (oracle::exact::abs(Rational(rational(a) * rational(b))) <
        oracle::exact::power_of_two(kWellAboveUnderflow<T>)) {
      continue;  // a subnormal operand lost bits and took the product below the range
    }
    check_two_prod(tally, a, b);
  }
  EXPECT_GT(tally.cases(), kRandomCases * 9 / 10);
  tally.expect_no_failure();
}

TYPED_TEST(ErrorFree, twoProdFallsBackOnFmaNearOverflowAndStaysExact) {
  using T = TypeParam;
  Generator<T> g(0xe0f4);
  Tally tally("two_prod near overflow, an operand past the threshold");
  // |a| >= 2^kFallbackExponent (the std::fma path), b such that the product is finite: up to
  // the top binade, where the product may round to infinity (skipped).
  for (int i = 0; i < kRandomCases; ++i) {
    const T a = g.value(kFallbackExponent<T>, kMaxExponent<T> - 1);
    const int product = g.integer(kMaxExponent<T> - 2 * kDigits<T>, kMaxExponent<T> - 1);
    const T b = g.at(product - std::ilogb(a));
    if (!std::isfinite(a * b)) continue;
    check_two_prod(tally, a, b);
    check_two_prod(tally, b, a);
  }
  EXPECT_GT(tally.cases(), kRandomCases);
  tally.expect_no_failure();
}

TYPED_TEST(ErrorFree, twoProdIsExactForAFiniteProductNearOverflowOfOperandsBelowTheThreshold) {
  // The header: exact "unless |a| or |b| is within 2^(p/2 + 2) of overflow". Dekker's
  // x.hi * y.hi can round past the largest finite value when the product itself does not.
  using T = TypeParam;
  Generator<T> g(0xe0f5);
  Tally tally("two_prod near overflow, both operands below the threshold");
  constexpr int p = kDigits<T>, half = kMaxExponent<T> / 2;
  // Both split to 2^half, whose square overflows; their product rounds to a finite value.
  const T just_below = std::ldexp(T(1) - std::ldexp(T(1), 4 - p), half);
  check_two_prod(tally, just_below, just_below);
  for (int i = 0; i < kRandomCases; ++i) {
    const int product = kMaxExponent<T> - 1 - g.integer(0, 1);
    const int ea = g.integer(product - kFallbackExponent<T> + 1, kFallbackExponent<T> - 1);
    const T a = g.at(ea), b = g.at(product - ea);
    if (!std::isfinite(a * b)) continue;
    check_two_prod(tally, a, b);
  }
  EXPECT_GT(tally.cases(), kRandomCases / 2);
  tally.expect_no_failure();
}

TYPED_TEST(ErrorFree, splitIsExactAndEachHalfFitsInHalfTheSignificand) {
  using T = TypeParam;
  Generator<T> g(0xe0f6);
  Tally tally("split");
  constexpr int p = kDigits<T>;
  const auto check = [&](T a) {
    const Pair<T> s = split(a);
    const bool ok = finite(s) && rational(s) == rational(a) &&
                    significant_bits(rational(s.hi)) <= p / 2 &&
                    significant_bits(rational(s.lo)) <= p / 2;
    tally.check(ok, [&] {
      return "split(" + hex(a) + ") = " + hex(s) + ", bits " +
             std::to_string(significant_bits(rational(s.hi))) + " + " +
             std::to_string(significant_bits(rational(s.lo)));
    });
  };
  const T half_ulp = std::ldexp(T(1), -p);
  for (T a : {T(0), T(1), T(1) - half_ulp, T(1) + 2 * half_ulp, T(1) / T(3), T(2) / T(3),
              std::numeric_limits<T>::denorm_min(), std::numeric_limits<T>::min(),
              std::numeric_limits<T>::min() - std::numeric_limits<T>::denorm_min(),
              std::nextafter(std::ldexp(T(1), kFallbackExponent<T>), T(0))}) {
    check(a);
    check(-a);
  }
  // The range split() serves two_prod in: subnormals to the fallback threshold.
  for (int i = 0; i < kRandomCases; ++i) {
    check(g.value(kLowestExponent<T>, kFallbackExponent<T> - 1));
  }
  tally.expect_no_failure();
}

/// The terms of a random sum: well-conditioned ones over a wide exponent range; cancelling
/// ones (x, -x, y, ... plus a few small terms, shuffled) whose exact sum is tiny against the
/// terms, or zero; nearly cancelling pairs; exact products as two terms.
template <class T>
std::vector<T> random_terms(Generator<T>& g) {
  constexpr int span = std::min(kMaxExponent<T> / 4, 300);
  std::vector<T> terms;
  switch (g.integer(0, 4)) {
    case 0:
      for (int i = g.integer(1, 24); i > 0; --i) terms.push_back(g.value(-span, span));
      break;
    case 1:  // exact cancellation, a few small terms left
    case 2: {
      for (int i = g.integer(1, 10); i > 0; --i) {
        const T x = g.value(-span, span);
        terms.push_back(x);
        terms.push_back(-x);
      }
      for (int i = g.integer(0, 3); i > 0; --i) terms.push_back(g.value(-span, -span / 2));
      break;
    }
    case 3: {  // nearly cancelling pairs: x and -(x + a few ulps)
      for (int i = g.integer(1, 8); i > 0; --i) {
        const T x = g.value(-span, span);
        terms.push_back(x);
        terms.push_back(-(x + T(g.integer(-3, 3)) * ulp(x)));
      }
      break;
    }
    default: {  // products, exactly, and their cancellation
      for (int i = g.integer(1, 6); i > 0; --i) {
        const T a = g.value(-span / 2, span / 2), b = g.value(-span / 2, span / 2);
        const Pair<T> p = two_prod(a, b);
        terms.push_back(p.hi);
        terms.push_back(p.lo);
        if (g.coin()) terms.push_back(-p.hi);
      }
    }
  }
  g.shuffle(terms);
  return terms;
}

template <class T, std::size_t Capacity>
Rational exact_sum(const Terms<T, Capacity>& terms) {
  Rational s = 0;
  for (std::size_t i = 0; i < terms.size(); ++i) s += rational(terms[i]);
  return s;
}

template <class T>
std::string describe(const std::vector<T>& terms) {
  std::string out = "terms";
  for (T x : terms) out += " " + hex(x);
  return out;
}

/// Ogita, Rump and Oishi's bounds for SumK on n terms with exact sum s and magnitude S (u the
/// unit roundoff): Sum (K = 1) gamma_{n-1} S; Sum2 u |s| + gamma_{n-1}^2 S (their Prop. 4.5);
/// SumK (u + 3 gamma_{n-1}^2) |s| + gamma_{2n-2}^K S (their Prop. 4.10).
template <class T>
Rational sum_k_bound(int k, long n, const Rational& s, const Rational& magnitude) {
  if (n <= 1) return 0;
  const Rational u = unit_roundoff<T>();
  const Rational g = gamma<T>(n - 1);
  if (k == 1) return g * magnitude;
  if (k == 2) return u * oracle::exact::abs(s) + g * g * magnitude;
  Rational power = 1;
  for (int i = 0; i < k; ++i) power *= gamma<T>(2 * n - 2);
  return (u + 3 * g * g) * oracle::exact::abs(s) + power * magnitude;
}

constexpr int kRandomSums = 600;

TYPED_TEST(ErrorFree, sumKIsWithinOgitaRumpOishiBoundAndKeepsTheExactSum) {
  using T = TypeParam;
  using Sum = Terms<T, 64>;
  Generator<T> g(0xe0f7);
  Tally bound("Terms::sum(k) within SumK's bound"), kept("Terms::sum(k) keeps the exact sum"),
      magnitude("Terms::magnitude() within gamma_{n-1} of the exact one");
  int cancelled = 0;
  for (int i = 0; i < kRandomSums; ++i) {
    const std::vector<T> added = random_terms(g);
    Sum terms;
    for (T x : added) terms.add(x);
    const Rational s = exact_sum(terms);
    Rational total_magnitude = 0;
    for (T x : added) total_magnitude += oracle::exact::abs(rational(x));
    const auto n = static_cast<long>(terms.size());
    if (n > 1 && oracle::exact::abs(s) * (1 << 20) < total_magnitude) ++cancelled;
    magnitude.check(oracle::exact::abs(rational(terms.magnitude()) - total_magnitude) <=
                        (n > 1 ? gamma<T>(n - 1) : Rational(0)) * total_magnitude,
                    [&] { return describe(added) + ": magnitude " + hex(terms.magnitude()); });
    for (int k = 1; k <= 3; ++k) {
      Sum copy = terms;
      const T result = copy.sum(k);
      const Rational error = oracle::exact::abs(rational(result) - s);
      const Rational limit = sum_k_bound<T>(k, n, s, total_magnitude);
      bound.check(std::isfinite(result) && error <= limit, [&] {
        return describe(added) + ": sum(" + std::to_string(k) + ") = " + hex(result) + ", error " +
               decimal(error) + " > bound " + decimal(limit);
      });
      kept.check(copy.size() == terms.size() && exact_sum(copy) == s,
                 [&] { return describe(added) + ": sum(" + std::to_string(k) + ")"; });
    }
  }
  EXPECT_GT(cancelled, kRandomSums / 4);  // the ill-conditioned sums are there
  bound.expect_no_failure();
  kept.expect_no_failure();
  magnitude.expect_no_failure();
}

TYPED_TEST(ErrorFree, sumKOnHandMadeCancellations) {
  using T = TypeParam;
  Tally tally("Terms::sum(k) on hand-made sums");
  constexpr int p = kDigits<T>;
  const T big = std::ldexp(T(1), p + 2), small = std::ldexp(T(1), -p);
  const std::vector<std::vector<T>> sums = {
      {},
      {T(1)},
      {big, T(1), -big},
      {big, small, T(1), -big},
      {T(1), big, small, -big, -T(1)},
      {big, -big, big, -big},
      {std::ldexp(T(1), kMaxExponent<T> - 8), T(3), -std::ldexp(T(1), kMaxExponent<T> - 8)},
      {T(1), small / 2, small / 2},
  };
  for (const auto& added : sums) {
    Terms<T, 16> terms;
    for (T x : added) terms.add(x);
    const Rational s = exact_sum(terms);
    Rational total_magnitude = 0;
    for (T x : added) total_magnitude += oracle::exact::abs(rational(x));
    for (int k = 1; k <= 3; ++k) {
      Terms<T, 16> copy = terms;
      const T result = copy.sum(k);
      const Rational limit = sum_k_bound<T>(k, static_cast<long>(terms.size()), s, total_magnitude);
      tally.check(oracle::exact::abs(rational(result) - s) <= limit, [&] {
        return describe(added) + ": sum(" + std::to_string(k) + ") = " + hex(result);
      });
    }
    // Three passes leave a plain x, y, -x style cancellation exact.
    if (added.size() == 3 && added[0] == big) {
      Terms<T, 16> copy = terms;
      tally.check(rational(copy.sum(3)) == s, [&] { return describe(added) + ": sum(3) exact"; });
    }
  }
  tally.expect_no_failure();
}

TYPED_TEST(ErrorFree, termsDropZerosAndTermsBeyondCapacityAndAddProductsExactly) {
  using T = TypeParam;
  Terms<T, 3> terms;
  terms.add(T(0));
  terms.add(-T(0));
  EXPECT_EQ(terms.size(), 0u);
  EXPECT_EQ(terms.sum(2), T(0));
  terms.add_product(T(1) / T(3), T(3) + std::ldexp(T(1), 2 - kDigits<T>));
  ASSERT_EQ(terms.size(), 2u);
  EXPECT_EQ(rational(terms[0]) + rational(terms[1]),
            rational(T(1) / T(3)) * rational(T(3) + std::ldexp(T(1), 2 - kDigits<T>)));
  terms.add(Pair<T>{T(5), T(0)});
  terms.add(T(7));  // beyond the capacity
  EXPECT_EQ(terms.size(), 3u);
  EXPECT_TRUE(terms.all_finite());
  EXPECT_EQ((Terms<T, 3>::capacity()), 3u);
  EXPECT_EQ(rational(terms[2]), 5);
}

/// distil()'s claims, each with its own tally: the flag (and the terms' exact sum unchanged,
/// 0 + 0 for a zero sum), hi the rounding of the exact sum s, lo the rounding of the rest s - hi,
/// and the pair within eps |lo| of s.
struct DistilTallies {
  Tally flag{"Terms::distil sets the flag, keeps the exact sum, gives 0 + 0 for 0"};
  Tally hi{"Terms::distil's hi is the rounding of the exact sum"};
  Tally lo{"Terms::distil's lo is the rounding of the rest (exact sum - hi)"};
  Tally bound{"Terms::distil's pair is within eps |lo| of the exact sum"};
  void expect_no_failure() const {
    flag.expect_no_failure();
    hi.expect_no_failure();
    lo.expect_no_failure();
    bound.expect_no_failure();
  }
};

template <class T, std::size_t Capacity>
void check_distil(DistilTallies& tallies, const Terms<T, Capacity>& terms, const std::string& what,
                  int max_passes = 8) {
  Terms<T, Capacity> copy = terms;
  const Rational s = exact_sum(terms);
  bool exact = false;
  const Pair<T> d = copy.distil(exact, max_passes);
  const T rounded = oracle::exact::round_to<T>(s);
  const auto describe = [&] {
    return what + ": distil = " + hex(d) + (exact ? "" : " (not exact)") + ", rounded sum " +
           hex(rounded);
  };
  const bool settled = exact && finite(d) && exact_sum(copy) == s;
  tallies.flag.check(settled && (s != 0 || (d.hi == T(0) && d.lo == T(0))), describe);
  if (!settled || s == 0) return;
  tallies.hi.check(d.hi == rounded, describe);
  const Rational rest = s - rational(d.hi);
  tallies.lo.check(d.lo == oracle::exact::round_to<T>(rest), [&] {
    return describe() + ", rounded rest " + hex(oracle::exact::round_to<T>(rest));
  });
  const Rational eps = oracle::exact::power_of_two(1 - kDigits<T>);
  const Rational error = oracle::exact::abs(rational(d) - s);
  tallies.bound.check(error <= eps * oracle::exact::abs(rational(d.lo)), [&] {
    return describe() + ", error " + decimal(error) + " = " +
           std::to_string(Rational(error / (eps * oracle::exact::abs(rational(d.lo)))).get_d()) +
           " eps |lo|";
  });
}

TYPED_TEST(ErrorFree, distilGivesTheRoundedSumAndTheRoundedRest) {
  using T = TypeParam;
  Generator<T> g(0xe0f8);
  DistilTallies tally;
  int beyond_default = 0, most_passes = 0;
  for (int i = 0; i < kRandomSums; ++i) {
    const std::vector<T> added = random_terms(g);
    Terms<T, 64> terms;
    for (T x : added) terms.add(x);
    // The default 8 passes do not always suffice (the flag says so): as many as needed.
    int passes = 1;
    for (bool exact = false; passes < 1000; ++passes) {
      Terms<T, 64> copy = terms;
      copy.distil(exact, passes);
      if (exact) break;
    }
    beyond_default += passes > 8;
    most_passes = std::max(most_passes, passes);
    check_distil(tally, terms, describe(added), passes);
  }
  std::printf("[ measured ] distil<%s>: %d of %d random sums need more than 8 passes, at most %d\n",
              type_name<T>(), beyond_default, kRandomSums, most_passes);
  constexpr int p = kDigits<T>;
  const T big = std::ldexp(T(1), p + 2);
  for (const std::vector<T>& added :
       std::vector<std::vector<T>>{{}, {T(1)}, {big, -big}, {big, T(1), -big, T(-1)}}) {
    Terms<T, 8> terms;
    for (T x : added) terms.add(x);
    check_distil(tally, terms, describe(added));
  }
  tally.expect_no_failure();
}

TYPED_TEST(ErrorFree, distilRoundsAWorkingPrecisionTieThatALowerTermBreaks) {
  // 1 + u + u^2 / 16 (u = 2^-p): its rounding is 1 + 2u, as the lower term breaks the tie
  // 1 + u. The terms 1, u, u^2/16 are settled (no TwoSum changes them), and the rest's rounding
  // u then ties with 1 in fast_two_sum, which rounds to even.
  using T = TypeParam;
  DistilTallies tally;
  constexpr int p = kDigits<T>;
  for (T sign : {T(1), T(-1)}) {
    Terms<T, 8> terms;
    terms.add(sign * std::ldexp(T(1), -2 * p - 4));
    terms.add(sign * std::ldexp(T(1), -p));
    terms.add(sign);
    check_distil(tally, terms, "terms +-{2^(-2p-4), 2^-p, 1}");
  }
  tally.expect_no_failure();
}

/// The largest measured error of a double-word operation in units of u^2 |exact|.
struct Ratio {
  double largest = 0;
  std::string input;
};

template <class T>
void measure(Ratio& ratio, Tally& tally, const Rational& computed, const Rational& expected,
             int bound_in_u2, const std::string& what) {
  const Rational u = unit_roundoff<T>();
  const Rational error = oracle::exact::abs(computed - expected);
  const double r = Rational(error / (u * u * oracle::exact::abs(expected))).get_d();
  if (r > ratio.largest) ratio = {r, what};
  tally.check(error <= bound_in_u2 * u * u * oracle::exact::abs(expected),
              [&] { return what + ": error " + std::to_string(r) + " u^2 of the exact value"; });
}

template <class T>
void report(const char* operation, const Ratio& ratio, int bound_in_u2) {
  std::printf("[ measured ] %s<%s>: largest error %.4g u^2 |exact| (bound %d u^2) at %s\n",
              operation, type_name<T>(), ratio.largest, bound_in_u2, ratio.input.c_str());
}

/// Exponents of the double-word operands: well inside the normal range, so that no partial
/// result nears underflow or overflow.
template <class T>
constexpr int kPairSpan = std::min(kMaxExponent<T> / 4, 400);

constexpr int kDoubleWordCases = 6000;

/// A divisor or factor b (its significand random, or just above 1, just below 2, or short).
template <class T>
T random_operand(Generator<T>& g) {
  return g.value(-kPairSpan<T>, kPairSpan<T>);
}

/// A double-word operation `op(a, b)` against its exact value `exact(a, b)` on random operands
/// (a a normalized pair, b from `operand`), within `bound` u^2 of the exact value.
template <class T, class Operand, class Op, class Exact>
void check_double_word(const char* name, int bound, std::uint64_t seed, Operand operand, Op op,
                       Exact exact) {
  Generator<T> g(seed);
  Tally tally(std::string(name) + " within " + std::to_string(bound) + "u^2");
  Ratio ratio;
  for (int i = 0; i < kDoubleWordCases; ++i) {
    const Pair<T> a = g.pair(-kPairSpan<T>, kPairSpan<T>);
    const auto b = operand(g);
    const Pair<T> r = op(a, b);
    const std::string what = std::string(name) + "(" + hex(a) + ", " + hex(b) + ") = " + hex(r);
    if (!finite(r)) {
      tally.check(false, [&] { return what; });
      continue;
    }
    measure<T>(ratio, tally, rational(r), exact(rational(a), rational(b)), bound, what);
  }
  report<T>(name, ratio, bound);
  tally.expect_no_failure();
}

template <class T>
Pair<T> random_pair_operand(Generator<T>& g) {
  return g.pair(-kPairSpan<T>, kPairSpan<T>);
}
const auto product = [](const Rational& a, const Rational& b) { return Rational(a * b); };
const auto quotient = [](const Rational& a, const Rational& b) { return Rational(a / b); };

TYPED_TEST(ErrorFree, multiplyPairByScalarIsWithin3uSquared) {
  using T = TypeParam;
  check_double_word<T>(
      "multiply(Pair, T)", 3, 0xe0f9, random_operand<T>,
      [](Pair<T> a, T b) { return multiply(a, b); }, product);
}

TYPED_TEST(ErrorFree, dividePairByScalarIsWithin8uSquared) {
  // The header says "to about twice the working precision"; 8u^2 is the analysis' bound.
  using T = TypeParam;
  check_double_word<T>(
      "divide(Pair, T)", 8, 0xe0fa, random_operand<T>, [](Pair<T> a, T b) { return divide(a, b); },
      quotient);
}

TYPED_TEST(ErrorFree, dividePairByPairIsWithin18uSquared) {
  using T = TypeParam;
  check_double_word<T>(
      "divide(Pair, Pair)", 18, 0xe0fb, random_pair_operand<T>,
      [](Pair<T> a, Pair<T> b) { return divide(a, b); }, quotient);
}

TYPED_TEST(ErrorFree, dividePairByScalarWithItsReciprocalIsWithin17uSquared) {
  // The perspective fast path's division: the reciprocal fl(1 / b) computed once, no division.
  using T = TypeParam;
  check_double_word<T>(
      "divide(Pair, T, 1 / b)", 17, 0xe100, random_operand<T>,
      [](Pair<T> a, T b) { return divide(a, b, T(1) / b); }, quotient);
}

TYPED_TEST(ErrorFree, dividePairByPairWithItsReciprocalIsWithin28uSquared) {
  using T = TypeParam;
  check_double_word<T>(
      "divide(Pair, Pair, 1 / b.hi)", 28, 0xe101, random_pair_operand<T>,
      [](Pair<T> a, Pair<T> b) { return divide(a, b, T(1) / b.hi); }, quotient);
}

TYPED_TEST(ErrorFree, multiplyPairsIsWithin7uSquared) {
  using T = TypeParam;
  check_double_word<T>(
      "multiply(Pair, Pair)", 7, 0xe103, random_pair_operand<T>,
      [](Pair<T> a, Pair<T> b) { return multiply(a, b); }, product);
}

TYPED_TEST(ErrorFree, addPairsIsWithin3uSquaredOfTheSumEvenWhenItCancels) {
  // The bound is relative to the exact sum itself: cancellation must not spoil it.
  using T = TypeParam;
  Generator<T> g(0xe102);
  Tally tally("add(Pair, Pair) within 3u^2 / (1 - 4u) of the sum");
  const Rational u = unit_roundoff<T>();
  const Rational bound = 3 * u * u / (1 - 4 * u);
  double largest = 0;
  for (int i = 0; i < kDoubleWordCases; ++i) {
    const Pair<T> a = g.pair(-kPairSpan<T>, kPairSpan<T>);
    Pair<T> b = g.pair(-kPairSpan<T>, kPairSpan<T>);
    if (g.coin()) {
      // Near -a: the high words cancel (a few ulps apart), the low words decide.
      T hi = -a.hi;
      for (int steps = g.integer(0, 3); steps > 0; --steps) {
        hi = std::nextafter(hi, g.coin() ? std::numeric_limits<T>::infinity()
                                         : -std::numeric_limits<T>::infinity());
      }
      b = {hi, g.coin() ? -a.lo : g.fraction() * ulp(hi) / T(4)};
    }
    const Pair<T> r = add(a, b);
    const Rational exact = rational(a) + rational(b);
    const Rational error = oracle::exact::abs(rational(r) - exact);
    const std::string what = "add(" + hex(a) + ", " + hex(b) + ") = " + hex(r);
    if (exact == 0) {
      tally.check(finite(r) && rational(r) == 0, [&] { return what + ", exact sum 0"; });
      continue;
    }
    largest = std::max(largest, Rational(error / (u * u * oracle::exact::abs(exact))).get_d());
    tally.check(finite(r) && error <= bound * oracle::exact::abs(exact), [&] { return what; });
  }
  std::printf("[ measured ] add(Pair, Pair)<%s>: largest error %.4g u^2 |sum| (bound 3 u^2)\n",
              type_name<T>(), largest);
  tally.expect_no_failure();
}

TYPED_TEST(ErrorFree, twoProdWithTheHardwareFmaFlavourIsTheSameExactPair) {
  // Fma::hardware is what the run-time FMA dispatch compiles; here it calls std::fma. Both
  // flavours must give the exact pair (long double has no hardware flavour: Dekker in both).
  using T = TypeParam;
  Generator<T> g(0xe104);
  for (int i = 0; i < kDoubleWordCases; ++i) {
    const T a = g.value(-kPairSpan<T>, kPairSpan<T>), b = g.value(-kPairSpan<T>, kPairSpan<T>);
    const Pair<T> hardware = two_prod<T, Fma::hardware>(a, b);
    const Pair<T> portable = two_prod<T, Fma::portable>(a, b);
    ASSERT_EQ(rational(hardware), rational(a) * rational(b)) << hex(a) << " " << hex(b);
    ASSERT_EQ(hardware.hi, portable.hi);
    ASSERT_EQ(hardware.lo, portable.lo);
  }
}

// round_pair<N, T>: the pair's value rounded to the narrower N, against oracle::exact::round_to<N>.

template <class Types>
class RoundPair : public ::testing::Test {};
using NarrowWide = ::testing::Types<std::pair<float, double>, std::pair<double, long double>>;
TYPED_TEST_SUITE(RoundPair, NarrowWide);

/// Checks round_pair<N>(hi + lo) against the exact rounding (and its sign, for a nonzero value).
template <class N, class T>
void check_round_pair(Tally& tally, T hi, T lo) {
  const N rounded = round_pair<N>(Pair<T>{hi, lo});
  const Rational value = rational(hi) + rational(lo);
  const N expected = oracle::exact::round_to<N>(value);
  const bool same_sign = value == 0 || std::signbit(rounded) == std::signbit(expected);
  tally.check(rounded == expected && same_sign, [&] {
    return "round_pair(" + hex(Pair<T>{hi, lo}) + ") = " + hex(rounded) + ", correctly rounded " +
           hex(expected);
  });
}

/// A tiny second word for hi: a fraction of its ulp (so fl(hi + lo) = hi), of either sign.
template <class T>
std::vector<T> tiny_words(T hi) {
  const T quarter = ulp(hi) / T(4);
  return {T(0),
          quarter,
          -quarter,
          std::ldexp(ulp(hi), -kDigits<T>),
          -std::ldexp(ulp(hi), -kDigits<T>),
          std::numeric_limits<T>::denorm_min(),
          -std::numeric_limits<T>::denorm_min()};
}

/// hi at the midpoint of the N values v and its neighbour towards `direction`, and just off it
/// on both sides, each with the tiny words.
template <class N, class T>
void check_around_midpoint(Tally& tally, N v, N direction) {
  const N w = std::nextafter(v, direction);
  if (!std::isfinite(w)) return;  // past the largest value: a test of its own
  const T mid = (static_cast<T>(v) + static_cast<T>(w)) / T(2);  // exact: T is wider
  for (T hi : {mid, std::nextafter(mid, T(0)), std::nextafter(mid, 4 * mid)}) {
    for (T lo : tiny_words(hi)) check_round_pair<N>(tally, hi, lo);
  }
}

TYPED_TEST(RoundPair, tiesAndNearTiesRoundAsTheExactValue) {
  using N = typename TypeParam::first_type;
  using T = typename TypeParam::second_type;
  Generator<N> g(0xe0fc);
  Tally tally("round_pair at ties");
  const N inf = std::numeric_limits<N>::infinity();
  for (int i = 0; i < kRandomCases / 4; ++i) {
    const N v = g.value(kMinExponent<N> - 1, kMaxExponent<N> - 2);
    check_around_midpoint<N, T>(tally, v, inf);
    check_around_midpoint<N, T>(tally, v, -inf);
  }
  // Midpoints on both sides of powers of two, where N's spacing changes.
  for (int e = kMinExponent<N> - 1; e < kMaxExponent<N>; e += g.integer(1, 9)) {
    const N power = std::ldexp(N(1), e);
    for (N v : {power, -power}) {
      check_around_midpoint<N, T>(tally, v, inf);
      check_around_midpoint<N, T>(tally, v, -inf);
    }
  }
  tally.expect_no_failure();
}

TYPED_TEST(RoundPair, subnormalResultsRoundAsTheExactValue) {
  using N = typename TypeParam::first_type;
  using T = typename TypeParam::second_type;
  Generator<N> g(0xe0fd);
  Tally tally("round_pair below N's normal range");
  const N inf = std::numeric_limits<N>::infinity();
  const N tiny = std::numeric_limits<N>::denorm_min(), smallest = std::numeric_limits<N>::min();
  for (N v : {N(0), tiny, 2 * tiny, 3 * tiny, smallest - tiny, smallest, -tiny, -smallest}) {
    check_around_midpoint<N, T>(tally, v, inf);
    check_around_midpoint<N, T>(tally, v, -inf);
  }
  for (int i = 0; i < kRandomCases / 4; ++i) {
    const N v = g.value(kLowestExponent<N>, kMinExponent<N> - 2);
    check_around_midpoint<N, T>(tally, v, inf);
    check_around_midpoint<N, T>(tally, v, -inf);
  }
  // Well below half the smallest subnormal: zero of the pair's sign.
  const T far_below = std::ldexp(static_cast<T>(tiny), -3);
  for (T hi : {far_below, -far_below}) {
    for (T lo : tiny_words(hi)) check_round_pair<N>(tally, hi, lo);
  }
  tally.expect_no_failure();
}

TYPED_TEST(RoundPair, randomPairsRoundAsTheExactValue) {
  using N = typename TypeParam::first_type;
  using T = typename TypeParam::second_type;
  Generator<T> g(0xe0fe);
  Tally tally("round_pair on random pairs");
  for (int i = 0; i < kRandomCases; ++i) {
    // From below N's subnormals to N's overflow threshold and a little past it.
    const Pair<T> x = g.pair(kLowestExponent<N> - 4, kMaxExponent<N> + 1);
    check_round_pair<N>(tally, x.hi, x.lo);
  }
  tally.expect_no_failure();
}

TYPED_TEST(RoundPair, pastTheLargestFiniteValueRoundsAsTheExactValue) {
  // Past N's largest value: infinity beyond the midpoint between it and 2^max_exponent (which
  // rounds to even, to infinity), the largest value below that midpoint, by lo's sign at it.
  using N = typename TypeParam::first_type;
  using T = typename TypeParam::second_type;
  Tally tally("round_pair past N's largest value");
  const T max = static_cast<T>(std::numeric_limits<N>::max());
  const T overflow = std::ldexp(T(1), kMaxExponent<N>);
  const T midpoint = (max + overflow) / 2;
  for (T hi : {max, std::nextafter(max, overflow), std::nextafter(midpoint, T(0)),
               std::nextafter(midpoint, overflow), overflow, 4 * overflow,
               std::numeric_limits<T>::max()}) {
    for (T lo : tiny_words(hi)) {
      check_round_pair<N>(tally, hi, lo);
      check_round_pair<N>(tally, -hi, -lo);
    }
  }
  tally.expect_no_failure();
}

TYPED_TEST(RoundPair, theOverflowMidpointRoundsByTheSignOfLo) {
  // hi = the midpoint between N's largest value and 2^max_exponent: fl_N(hi) is infinity, but
  // hi + lo with lo < 0 lies below the midpoint and rounds to the largest finite value.
  using N = typename TypeParam::first_type;
  using T = typename TypeParam::second_type;
  Tally tally("round_pair at the overflow midpoint");
  const T max = static_cast<T>(std::numeric_limits<N>::max());
  const T midpoint = (max + std::ldexp(T(1), kMaxExponent<N>)) / 2;
  for (T lo : tiny_words(midpoint)) {
    check_round_pair<N>(tally, midpoint, lo);
    check_round_pair<N>(tally, -midpoint, -lo);
  }
  tally.expect_no_failure();
}

TEST(RoundPairWider, aPairOfDoublesRoundsOnceToLongDouble) {
  // round_pair<long double>(Pair<double>) adds the two words in long double: one rounding of
  // their exact sum (x87: 64 bits hold at most 64 of the pair's up to 106).
  if constexpr (std::numeric_limits<long double>::digits > std::numeric_limits<double>::digits) {
    Generator<double> g(0xe105);
    Tally tally("round_pair<long double>(Pair<double>)");
    const auto check = [&](Pair<double> x) {
      const long double rounded = round_pair<long double>(x);
      const long double expected = oracle::exact::round_to<long double>(rational(x));
      tally.check(rounded == expected, [&] { return "round_pair(" + hex(x) + ")"; });
    };
    for (int i = 0; i < kRandomCases; ++i) check(g.pair(-300, 300));
    // Ties in long double, and their neighbours: 1 + 2^-64 (+- 2^-100).
    for (double sign : {1.0, -1.0}) {
      check({sign, sign * std::ldexp(1.0, -64)});
      check({sign, sign * (std::ldexp(1.0, -64) + std::ldexp(1.0, -100))});
      check({sign, sign * (std::ldexp(1.0, -64) - std::ldexp(1.0, -100))});
      check({sign * 3, sign * std::ldexp(1.0, -63)});
    }
    tally.expect_no_failure();
  } else {
    GTEST_SKIP() << "long double is no wider than double here";
  }
}

TYPED_TEST(ErrorFree, roundPairToTheSameTypeIsTheHighWord) {
  using T = TypeParam;
  Generator<T> g(0xe0ff);
  for (int i = 0; i < 200; ++i) {
    const Pair<T> x = g.pair(kLowestExponent<T> + kDigits<T>, kMaxExponent<T> - 1);
    EXPECT_EQ(round_pair<T>(x), x.hi) << hex(x);
    EXPECT_EQ(round_pair<T>(x), oracle::exact::round_to<T>(rational(x))) << hex(x);
  }
  const T inf = std::numeric_limits<T>::infinity();
  EXPECT_EQ(round_pair<T>(Pair<T>{inf, T(0)}), inf);
  EXPECT_EQ(round_pair<T>(Pair<T>{T(0), T(0)}), T(0));
}

}  // namespace
}  // namespace oblique::eft
