// libFuzzer target: the core (or OBLIQUE_IMPL) on decoded projections and planes. Aborts, naming
// the property, when an answer breaks the status contract, a property, or row 3's accuracy bound.
#include <cstdio>
#include <cstdlib>

#include "fuzz_input.h"
#include "oblique/properties/filtered.h"
#include "oblique/properties/implementations.h"
#include "oblique/properties/judge.h"
#include "oblique/protocol/numbers.h"

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
  using protocol::format_number;
  if (!describing()) return;
  std::fprintf(stderr, "exact status %s; acceptable: %s; Skeel condition %s; kappa %s\n",
               std::string(status_code(problem.exact_status())).c_str(),
               properties::status_list(problem.acceptable_statuses()).c_str(),
               format_number(problem.skeel_condition()).c_str(),
               format_number(problem.kappa().get_d()).c_str());
  if (outcome.status != Status::ok || problem.exact_status() != Status::ok) return;
  for (int i = 0; i < 4; ++i) {
    std::string row;
    for (int j = 0; j < 4; ++j) row += " " + format_number(outcome.projection(i, j));
    std::fprintf(stderr, "M' row %d:%s\n", i + 1, row.c_str());
  }
  std::string row;
  for (const auto& v : problem.exact_row3()) row += " " + format_number(v.get_d());
  std::fprintf(stderr, "exact row 3:%s\n", row.c_str());
  properties::Checks every;
  every.every = true;
  for (const auto& f : properties::judge(problem, outcome, every).checks) {
    if (!f.holds)
      std::fprintf(stderr, "%s: %s; residual %s, bound %s\n", f.kind.c_str(), f.relation.c_str(),
                   f.lhs.c_str(), f.rhs.c_str());
  }
}

template <class T>
void check(const oblique::fuzz::FuzzCase& c) {
  using namespace oblique;
  Matrix4<T> m;
  Vector4<T> plane;
  for (int i = 0; i < 16; ++i) m(i / 4, i % 4) = narrow<T>(c.matrix(i / 4, i % 4));
  for (int i = 0; i < 4; ++i) plane(i) = narrow<T>(c.plane(i));
  const properties::FilteredProblem<T> problem(m, plane, c.convention);
  static const auto implementations = properties::selected_implementations<T>();
  for (const auto& impl : implementations) {
    if (!impl.accepts(c.convention, m)) continue;
    const properties::Outcome<T> outcome = impl.run(m, plane, c.convention);
    // The core is also held to row 3's accuracy bound and to its ulps promise.
    const bool core = impl.name.rfind("core_", 0) == 0;
    const properties::Judgement judgement = properties::judge(problem, outcome, impl.checks(core));
    const properties::Finding* violation = judgement.violation();
    if (!violation) continue;
    explain(problem.exact(), outcome);
    std::fprintf(stderr, "oblique property violated: %s by %s (%s, %s, family %s, status %s)\n",
                 violation->kind.c_str(), impl.name.c_str(),
                 std::string(protocol::scalar_name<T>()).c_str(),
                 std::string(convention_name(c.convention)).c_str(), fuzz::family_label(c.family),
                 std::string(status_code(outcome.status)).c_str());
    std::abort();
  }
}

}  // namespace

/// With OBLIQUE_FUZZ_DESCRIBE set, prints the decoded case (for crash reports).
void describe(const oblique::fuzz::FuzzCase& c) {
  if (!describing()) return;
  std::fprintf(stderr, "scalar %s, convention %s, method %s, family %s\n",
               std::string(oblique::protocol::precision_name(c.scalar)).c_str(),
               std::string(oblique::convention_name(c.convention)).c_str(),
               std::string(oblique::method_name(c.method)).c_str(),
               oblique::fuzz::family_label(c.family));
  using oblique::protocol::format_number;
  using oblique::protocol::Notation;
  for (int i = 0; i < 5; ++i) {
    std::string decimal, hex;
    for (int j = 0; j < 4; ++j) {
      const double x = i < 4 ? c.matrix(i, j) : c.plane(j);
      decimal += " " + format_number(x);
      hex += (j ? " " : "") + format_number(x, Notation::hex);
    }
    if (i < 4)
      std::fprintf(stderr, "M row %d:%s  (%s)\n", i + 1, decimal.c_str(), hex.c_str());
    else
      std::fprintf(stderr, "C:%s  (%s)\n", decimal.c_str(), hex.c_str());
  }
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const oblique::fuzz::FuzzCase c = oblique::fuzz::decode(data, size);
  describe(c);
  switch (c.scalar) {
    case oblique::protocol::Precision::float32: check<float>(c); break;
    case oblique::protocol::Precision::float64: check<double>(c); break;
    case oblique::protocol::Precision::long_double: check<long double>(c); break;
  }
  return 0;
}
