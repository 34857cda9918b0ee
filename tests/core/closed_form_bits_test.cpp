// The closed form gives the answers it gave when they were checked, bit for bit: for every
// request in tests/data/closed_form_bits.txt (closed_form_bits.h; valid and invalid generated
// cases of every family and convention, special values in the entries, planes at the edges of
// the exponent range, stiff planes, far planes up to the top of the range), apply() answers with
// the same status, message, method, matrix and far corner.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "closed_form_bits.h"
#include "oblique/oblique.h"
#include "printers.h"
#include "same_bits.h"

namespace oblique {
namespace {

using test::parse_bits_token;
using test::same_bits;

/// How many lines of each scalar type were compared, and how many of those answers were ok.
struct Tally {
  long compared[3] = {};
  long ok[3] = {};
};

/// One line's request and expected answer, compared with apply()'s; false with `why` set when
/// the line cannot be read.
template <class T>
bool compare_line(std::istringstream& in, int scalar, Tally& tally, std::string& why) {
  std::string convention_token, method_token;
  in >> convention_token >> method_token;
  const std::optional<Convention> convention = parse_convention(convention_token);
  const std::optional<Method> method = parse_method(method_token);
  if (!convention || !method) {
    why = "unknown convention or method";
    return false;
  }
  const auto read = [&](T& x) {
    std::string token;
    in >> token;
    const std::optional<T> value = parse_bits_token<T>(token);
    if (value) x = *value;
    return value.has_value();
  };
  Matrix4<T> m;
  Vector4<T> c, row3, q;
  bool read_all = true;
  for (int i = 0; i < 16; ++i) read_all &= read(m(i / 4, i % 4));
  for (int i = 0; i < 4; ++i) read_all &= read(c(i));
  std::string status_token, ran_token;
  in >> status_token >> ran_token;
  for (int i = 0; i < 4; ++i) read_all &= read(row3(i));
  for (int i = 0; i < 4; ++i) read_all &= read(q(i));
  std::string detail;
  std::getline(in >> std::ws, detail);
  if (detail == "-") detail.clear();
  const std::optional<Status> status = parse_status(status_token);
  const std::optional<Method> ran = parse_method(ran_token);
  if (!read_all || !status || !ran) {
    why = "a number, status or method that does not read";
    return false;
  }
  Matrix4<T> expected = m;
  expected.row(2) = row3.transpose();
  const ObliqueResult<T> r = apply<T>(m, c, *convention, *method);
  ++tally.compared[scalar];
  tally.ok[scalar] += *status == Status::ok;
  EXPECT_TRUE(r.status == *status && r.detail == detail && r.method == *ran &&
              same_bits(r.projection, expected) && same_bits(r.far_corner, q))
      << test::scalar_token<T>() << ", " << convention_token << ", " << method_token << ": now "
      << status_code(r.status) << " (" << r.message() << ", " << method_name(r.method)
      << "), expected " << status_token << " ("
      << (detail.empty() ? std::string(status_message(*status)) : detail) << ", " << ran_token
      << ")\nM =\n"
      << m << "\nC = " << c.transpose() << "\nnow M' =\n"
      << r.projection << "\nexpected M' =\n"
      << expected << "\nnow Q = " << r.far_corner.transpose() << "\nexpected Q = " << q.transpose();
  return true;
}

TEST(ClosedFormBits, applyGivesTheKeptAnswers) {
  std::ifstream file(OBLIQUE_CLOSED_FORM_BITS);
  ASSERT_TRUE(file) << "cannot open " << OBLIQUE_CLOSED_FORM_BITS;
  Tally tally;
  std::string line;
  int number = 0;
  while (std::getline(file, line)) {
    ++number;
    std::istringstream in(line);
    std::string scalar, why;
    in >> scalar;
    bool read = false;
    if (scalar == test::scalar_token<float>()) {
      read = compare_line<float>(in, 0, tally, why);
    } else if (scalar == test::scalar_token<double>()) {
      read = compare_line<double>(in, 1, tally, why);
    } else if (scalar == test::scalar_token<long double>()) {
      read = compare_line<long double>(in, 2, tally, why);
    } else {
      why = "unknown scalar type " + scalar;
    }
    ASSERT_TRUE(read) << OBLIQUE_CLOSED_FORM_BITS << ":" << number << ": " << why;
    if (::testing::Test::HasFailure()) {
      ADD_FAILURE() << "at " << OBLIQUE_CLOSED_FORM_BITS << ":" << number;
      return;
    }
  }
  // Every scalar type read, with a good share of ok answers (not only refusals).
  for (int s = 0; s < 3; ++s) {
    EXPECT_GT(tally.compared[s], 500) << s;
    EXPECT_GT(tally.ok[s], tally.compared[s] / 5) << s;
  }
}

// The tokens read back what was written, NaN's sign and payload included, and a token that
// bits_token() cannot have written (not a number, a number that is not a T) is refused.
TEST(ClosedFormBits, tokensRoundTripAndRefuseWhatTheyCannotHold) {
  const double values[] = {
      0.0, -0.0, 0.1, -1e-310, 1.7976931348623157e308, std::numeric_limits<double>::infinity()};
  for (double x : values) EXPECT_TRUE(same_bits(*parse_bits_token<double>(test::bits_token(x)), x));
  const double negative_nan = -std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(same_bits(*parse_bits_token<double>(test::bits_token(negative_nan)), negative_nan));
  const long double third = 1.0L / 3.0L;
  EXPECT_TRUE(same_bits(*parse_bits_token<long double>(test::bits_token(third)), third));
  EXPECT_FALSE(parse_bits_token<float>(test::bits_token(0.1)));  // 0.1 in double is not a float
  EXPECT_FALSE(parse_bits_token<double>("0x1p+0junk"));
  EXPECT_FALSE(parse_bits_token<double>("nan:12"));
  EXPECT_FALSE(parse_bits_token<double>(""));
}

}  // namespace
}  // namespace oblique
