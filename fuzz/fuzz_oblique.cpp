// libFuzzer target: the core (or OBLIQUE_IMPL) on decoded projections and planes. Aborts, naming
// the property, when an answer breaks the status contract, a property, or row 3's accuracy bound.
#include <cstdio>
#include <cstdlib>

#include "fuzz_input.h"
#include "oblique/properties/judge.h"
#include "report.h"

namespace {

/// double -> T without undefined behaviour: out-of-range finite values become +-infinity.
template <class T>
T narrow(double x) {
  if (std::isfinite(x) && std::abs(x) > static_cast<double>(std::numeric_limits<T>::max())) {
    return std::signbit(x) ? -std::numeric_limits<T>::infinity()
                           : std::numeric_limits<T>::infinity();
  }
  return static_cast<T>(x);
}

bool describing() {
  static const bool enabled = std::getenv("OBLIQUE_FUZZ_DESCRIBE") != nullptr;
  return enabled;
}

/// With OBLIQUE_FUZZ_DESCRIBE set, prints what the checker knows of the case and the answer.
template <class T>
void explain(const oblique::properties::Problem<T>& problem,
             const oblique::properties::Outcome<T>& outcome) {
  using namespace oblique;
  if (!describing()) return;
  std::string acceptable;
  for (Status s : problem.acceptable_statuses())
    acceptable += (acceptable.empty() ? "" : ", ") + std::string(status_code(s));
  std::fprintf(stderr, "exact status %s; acceptable: %s; Skeel condition %.3g; kappa %.3g\n",
               std::string(status_code(problem.exact_status())).c_str(), acceptable.c_str(),
               problem.skeel_condition(), problem.kappa().get_d());
  if (outcome.status != Status::ok || problem.exact_status() != Status::ok) return;
  for (int i = 0; i < 4; ++i) {
    std::fprintf(stderr, "M' row %d: %.17Lg %.17Lg %.17Lg %.17Lg\n", i + 1,
                 static_cast<long double>(outcome.projection(i, 0)),
                 static_cast<long double>(outcome.projection(i, 1)),
                 static_cast<long double>(outcome.projection(i, 2)),
                 static_cast<long double>(outcome.projection(i, 3)));
  }
  const exact::Vec row = problem.exact_row3();
  std::fprintf(stderr, "exact row 3: %.17g %.17g %.17g %.17g\n", row[0].get_d(), row[1].get_d(),
               row[2].get_d(), row[3].get_d());
  for (const auto& v : problem.check(outcome.projection).items) {
    if (v.applies && !v.holds)
      std::fprintf(stderr, "%s: %s; residual %s, bound %s\n",
                   std::string(properties::property_name(v.property)).c_str(), v.relation.c_str(),
                   v.lhs.c_str(), v.rhs.c_str());
  }
}

template <class T>
void check(const oblique::fuzz::FuzzCase& c) {
  using namespace oblique;
  Matrix4<T> m;
  Vector4<T> plane;
  for (int i = 0; i < 16; ++i) m(i / 4, i % 4) = narrow<T>(c.matrix(i / 4, i % 4));
  for (int i = 0; i < 4; ++i) plane(i) = narrow<T>(c.plane(i));
  const properties::Problem<T> problem(m, plane, c.convention);
  static const auto implementations = properties::selected_implementations<T>();
  for (const auto& impl : implementations) {
    if (!impl.accepts(c.convention, m)) continue;
    const properties::Outcome<T> outcome = impl.run(m, plane, c.convention);
    const std::string violation =
        properties::first_violation(problem, impl, outcome, impl.name.rfind("core_", 0) == 0);
    if (violation.empty()) continue;
    explain(problem, outcome);
    std::fprintf(stderr, "oblique property violated: %s by %s (%s, %s, family %s, status %s)\n",
                 violation.c_str(), impl.name.c_str(), properties::scalar_name<T>(),
                 std::string(convention_name(c.convention)).c_str(), fuzz::family_label(c.family),
                 std::string(status_code(outcome.status)).c_str());
    std::abort();
  }
}

}  // namespace

/// With OBLIQUE_FUZZ_DESCRIBE set, prints the decoded case (for crash reports).
void describe(const oblique::fuzz::FuzzCase& c) {
  if (!describing()) return;
  const char* scalars[] = {"float", "double", "long_double"};
  std::fprintf(stderr, "scalar %s, convention %s, method %s, family %s\n",
               scalars[static_cast<int>(c.scalar)],
               std::string(oblique::convention_name(c.convention)).c_str(),
               std::string(oblique::method_name(c.method)).c_str(),
               oblique::fuzz::family_label(c.family));
  for (int i = 0; i < 4; ++i) {
    std::fprintf(stderr, "M row %d: %.17g %.17g %.17g %.17g  (%a %a %a %a)\n", i + 1,
                 c.matrix(i, 0), c.matrix(i, 1), c.matrix(i, 2), c.matrix(i, 3), c.matrix(i, 0),
                 c.matrix(i, 1), c.matrix(i, 2), c.matrix(i, 3));
  }
  std::fprintf(stderr, "C: %.17g %.17g %.17g %.17g  (%a %a %a %a)\n", c.plane(0), c.plane(1),
               c.plane(2), c.plane(3), c.plane(0), c.plane(1), c.plane(2), c.plane(3));
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const oblique::fuzz::FuzzCase c = oblique::fuzz::decode(data, size);
  describe(c);
  switch (c.scalar) {
    case oblique::fuzz::Scalar::float32: check<float>(c); break;
    case oblique::fuzz::Scalar::float64: check<double>(c); break;
    case oblique::fuzz::Scalar::long_double: check<long double>(c); break;
  }
  return 0;
}
