// What the consumer judges share (consumer_judging.h), and the words of a consumer finding
// (consumers.h); compiled once for float, double and long double.
#include "consumer_judging.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "oblique/oracle/algebra.h"
#include "oblique/oracle/problem.h"
#include "oblique/protocol/numbers.h"
#include "oblique/references/kept_region.h"
#include "recent.h"

namespace oblique::oracle::consumer_judging {

namespace {

// solve_error() is written once over its number type N: exact rationals, or certified intervals
// (certified::Num, whose comparisons throw certified::Undecided where they cannot decide, and the
// exact computation then answers). The few operations it takes beyond + - * /, for each:
using certified::Num;
using NumMat = algebra::Mat<Num>;

Rational magnitude(const Rational& x) {
  return oracle::exact::abs(x);
}
Num magnitude(const Num& x) {
  return certified::abs(x);
}
Rational larger(const Rational& x, const Rational& y) {
  return x < y ? y : x;
}
Num larger(const Num& x, const Num& y) {
  return certified::larger_of(x, y);
}
Rational smaller(const Rational& x, const Rational& y) {
  return y < x ? y : x;
}
Num smaller(const Num& x, const Num& y) {
  return certified::smaller_of(x, y);
}
bool is_less(const Rational& x, const Rational& y) {
  return x < y;
}
bool is_less(const Num& x, const Num& y) {
  return certified::less(x, y);
}
bool is_less_equal(const Rational& x, const Rational& y) {
  return x <= y;
}
bool is_less_equal(const Num& x, const Num& y) {
  return certified::less_equal(x, y);
}
/// A rational constant (a gamma, a unit roundoff) in N.
template <class N>
N number(const Rational& r) {
  if constexpr (std::is_same_v<N, Rational>)
    return r;
  else
    return certified_of(r);
}

/// The rows r and columns c of m's 3 x 3 minor without row i and column j.
void minor_indices(int i, int j, int (&r)[3], int (&c)[3]) {
  for (int k = 0, n = 0; k < 4; ++k)
    if (k != i) r[n++] = k;
  for (int k = 0, n = 0; k < 4; ++k)
    if (k != j) c[n++] = k;
}

/// The six products of the minor of m without row i and column j, with their signs in its
/// determinant: permanent = false gives the determinant, true the permanent of its magnitudes
/// (the sum of the magnitudes of the products the cofactor of m_ij adds up).
template <class N>
N minor_sum(const algebra::Mat<N>& m, int i, int j, bool permanent) {
  int r[3], c[3];
  minor_indices(i, j, r, c);
  constexpr int kOrders[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {1, 0, 2}, {2, 1, 0}};
  N sum{};
  for (int k = 0; k < 6; ++k) {
    const auto& o = kOrders[k];
    const N p = m[r[0]][c[o[0]]] * m[r[1]][c[o[1]]] * m[r[2]][c[o[2]]];
    if (permanent)
      sum = sum + magnitude(p);
    else
      sum = k < 3 ? N(sum + p) : N(sum - p);
  }
  return sum;
}

/// One pivot order of an elimination with partial pivoting in T on m (consumers' solves), from
/// step k on: a holds the rows in pivot order, reduced through step k - 1, exactly; sum[r] bounds
/// the part of row r of |L||U| the steps before k gave; row_of[r] is the row of m at position r.
/// Entry by entry, `out` becomes the largest bound on |L^||U^| (rows in m's order) over every
/// pivot order rounding in T could take: at each step every candidate within the elimination's
/// error e = g sum of the largest is followed. The computed factors are bounded from the exact
/// ones: |u^| <= |u| + e and |l^| <= (|a_rk| + e_rk) / (|a_kk| - e_kk) (1 + u), at most 1 (the
/// pivot is the largest in T). False where a pivot is not determined in T (within e of 0).
template <class N>
bool lu_orders(algebra::Mat<N> a, algebra::Mat<N> sum, std::array<int, 4> row_of, int k, const N& g,
               const N& u, algebra::Mat<N>& out) {
  const N one = number<N>(1);
  N largest = number<N>(-1);
  int at = k;
  for (int r = k; r < 4; ++r) {
    if (is_less(largest, magnitude(a[r][k]))) {
      largest = magnitude(a[r][k]);
      at = r;
    }
  }
  const N reach = largest - g * sum[at][k];
  for (int r = k; r < 4; ++r) {
    const N e = g * sum[r][k];
    // (The largest itself is always followed: e >= 0.)
    if (r != at && is_less(magnitude(a[r][k]) + e, reach)) continue;
    if (is_less_equal(magnitude(a[r][k]), e)) return false;
    algebra::Mat<N> b = a, s = sum;
    std::array<int, 4> order = row_of;
    std::swap(b[r], b[k]);
    std::swap(s[r], s[k]);
    std::swap(order[r], order[k]);
    algebra::Vec<N> u_bar{};  // |u^| of the pivot row
    for (int c = k; c < 4; ++c) u_bar[c] = magnitude(b[k][c]) + g * s[k][c];
    for (int c = 0; c < 4; ++c) {
      const N row = s[k][c] + u_bar[c];
      out[order[k]][c] = larger(out[order[k]][c], row);
    }
    const N pivot_low = magnitude(b[k][k]) - g * s[k][k];
    for (int q = k + 1; q < 4; ++q) {
      const N l_bar = smaller(one, N((magnitude(b[q][k]) + g * s[q][k]) / pivot_low * (one + u)));
      const N l = b[q][k] / b[k][k];
      for (int c = k; c < 4; ++c) {
        s[q][c] = s[q][c] + l_bar * u_bar[c];
        if (c > k) b[q][c] = b[q][c] - l * b[k][c];
      }
      b[q][k] = N{};
    }
    if (k < 3 && !lu_orders(b, s, order, k + 1, g, u, out)) return false;
  }
  return true;
}

/// The 4 x 4 matrix whose every entry is kLuGrowth max|m| (tolerance.h, lu_entry_bound()).
template <class N>
algebra::Mat<N> lu_bound_of(const algebra::Mat<N>& m) {
  N largest{};
  for (const auto& row : m)
    for (const N& x : row) largest = larger(largest, magnitude(x));
  algebra::Mat<N> out;
  for (auto& row : out) row.fill(number<N>(oracle::tolerance::kLuGrowth) * largest);
  return out;
}

/// The bound on |L^||U^| for m's LU factors with partial pivoting computed in T (lu_orders()),
/// rows in m's order; the worst case, lu_bound(), where a pivot is not determined in T.
template <class T, class N>
algebra::Mat<N> lu_magnitudes(const algebra::Mat<N>& m, int bits) {
  algebra::Mat<N> out{}, sum{};
  for (auto& row : out) row.fill(N{});
  for (auto& row : sum) row.fill(N{});
  if (!lu_orders(m, sum, {0, 1, 2, 3}, 0,
                 number<N>(gamma_of<T>(oracle::tolerance::kSolveRoundings, bits)),
                 number<N>(unit<T>(bits)), out))
    return lu_bound_of(m);
  return out;
}

template <class N>
algebra::Mat<N> product(const algebra::Mat<N>& a, const algebra::Mat<N>& b) {
  algebra::Mat<N> out;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      N s{};
      for (int k = 0; k < 4; ++k) s = s + a[i][k] * b[k][j];
      out[i][j] = s;
    }
  }
  return out;
}

/// solve_error() in N: m and its inverse in N (exact, or enclosed).
template <class T, class N>
std::optional<algebra::Mat<N>> solve_error_in(const algebra::Mat<N>& m, const algebra::Mat<N>& inv,
                                              int bits) {
  const N one = number<N>(1);
  const N g = number<N>(gamma_of<T>(oracle::tolerance::kCofactorRoundings, bits));
  algebra::Mat<N> perm, abs_inv;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      perm[i][j] = minor_sum(m, i, j, true);
      abs_inv[i][j] = magnitude(inv[i][j]);
    }
  }
  N det{}, det_perm{};  // along row 0
  for (int j = 0; j < 4; ++j) {
    const N term = m[0][j] * minor_sum(m, 0, j, false);
    det = j % 2 == 0 ? N(det + term) : N(det - term);
    det_perm = det_perm + magnitude(m[0][j]) * perm[0][j];
  }
  const N size = magnitude(det);
  const N det_error = g * det_perm;
  if (!is_less(det_error, size)) return std::nullopt;
  // Applying the inverse: 4 roundings, and the window depth's conversion to NDC 2 more.
  const N g_apply = number<N>(gamma_of<T>(6, bits));
  const algebra::Mat<N> lu = product(product(abs_inv, lu_magnitudes<T>(m, bits)), abs_inv);
  const N g_lu = number<N>(gamma_of<T>(oracle::tolerance::kConsumerSolveRoundings, bits));
  algebra::Mat<N> out;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      const N& x = abs_inv[i][j];
      // adj_ij is the cofactor of m_ji; then the quotient (or the reciprocal and a product).
      const N e = (one + g) * (g * perm[j][i] + x * det_error) / (size - det_error) + g * x;
      out[i][j] = larger(N(e + g_apply * (x + e)), N(g_lu * lu[i][j]));
    }
  }
  return out;
}

/// The exact inverse of a finite matrix in T by its adjugate in integers: M = N 2^e (N integers,
/// exact::to_integers), so M^-1 = adj(N) / det(N) 2^-e; each entry one canonicalised quotient,
/// where elimination in rationals takes a gcd per operation. Empty where det N = 0.
template <class T>
std::optional<Mat> integer_inverse(const Matrix4<T>& matrix) {
  std::array<T, 16> flat;
  for (int i = 0; i < 16; ++i) flat[static_cast<std::size_t>(i)] = matrix(i / 4, i % 4);
  int exponent = 0;
  const std::array<oracle::exact::Integer, 16> entries = oracle::exact::to_integers(flat, exponent);
  oracle::exact::IntegerMat n;
  for (int i = 0; i < 16; ++i) n[i / 4][i % 4] = entries[static_cast<std::size_t>(i)];
  const oracle::exact::Integer det = oracle::exact::determinant(n);
  if (det == 0) return std::nullopt;
  Mat inv;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      // inv_ij = (-1)^(i + j) minor_ji / det: the minor of n without row j and column i.
      int r[3], c[3];
      for (int k = 0, a = 0, b = 0; k < 4; ++k) {
        if (k != j) r[a++] = k;
        if (k != i) c[b++] = k;
      }
      oracle::exact::Integer minor =
          n[r[0]][c[0]] * (n[r[1]][c[1]] * n[r[2]][c[2]] - n[r[1]][c[2]] * n[r[2]][c[1]]) -
          n[r[0]][c[1]] * (n[r[1]][c[0]] * n[r[2]][c[2]] - n[r[1]][c[2]] * n[r[2]][c[0]]) +
          n[r[0]][c[2]] * (n[r[1]][c[0]] * n[r[2]][c[1]] - n[r[1]][c[1]] * n[r[2]][c[0]]);
      if ((i + j) % 2 == 1) minor = -minor;
      Rational x(minor, det);
      x.canonicalize();
      // times 2^-exponent
      if (exponent > 0)
        mpq_div_2exp(x.get_mpq_t(), x.get_mpq_t(), static_cast<mp_bitcnt_t>(exponent));
      else if (exponent < 0)
        mpq_mul_2exp(x.get_mpq_t(), x.get_mpq_t(), static_cast<mp_bitcnt_t>(-exponent));
      inv[i][j] = x;
    }
  }
  return inv;
}

}  // namespace

/// The 4 x 4 matrix whose every entry is oracle::tolerance::lu_entry_bound(m): what |L||U| of m's
/// LU factors is at most, entry by entry.
Mat lu_bound(const Mat& m) {
  return lu_bound_of(m);
}

Mat mul(const Mat& a, const Mat& b) {
  return product(a, b);
}

Mat through_lu_bound(const Vec& a_rows, const Mat& m, const Mat& b) {
  const Rational bound = oracle::tolerance::lu_entry_bound(m);
  Vec columns;  // 1^T b
  for (int i = 0; i < 4; ++i) columns[i] = b[0][i] + b[1][i] + b[2][i] + b[3][i];
  Mat out;
  for (int i = 0; i < 4; ++i) {
    const Rational scaled = bound * a_rows[i];
    for (int j = 0; j < 4; ++j) out[i][j] = scaled * columns[j];
  }
  return out;
}

/// A bound S, entry by entry, on the error of v = M^-1 b computed in T by a correct
/// implementation: |v^ - v| <= S |b| (tolerance.h, "a solve with a projection"). The larger of
/// the two ways engines compute it, each bounded from this matrix rather than the worst case:
///  - an inverse by cofactors (adjugate over determinant), then applied: each cofactor within
///    gamma(kCofactorRoundings) of the permanent of its minor of |M|, the determinant within
///    that of the permanent of |M|; then 4 roundings applying it;
///  - an elimination with partial pivoting (an inverse, or an LU solve): backward error
///    gamma(kConsumerSolveRoundings) |L^||U^|, so gamma |M^-1| G |M^-1| with G = lu_magnitudes().
/// Empty where the determinant computed by cofactors is not determined in T.
template <class T>
std::optional<Mat> solve_error(const Mat& m, const Mat& inv, int bits) {
  return solve_error_in<T, Rational>(m, inv, bits);
}

Rational max_abs(const Vec& v) {
  Rational m = 0;
  for (const Rational& x : v) m = std::max(m, oracle::exact::abs(x));
  return m;
}

Rational sum_abs(const Vec& v) {
  Rational s = 0;
  for (const Rational& x : v) s += oracle::exact::abs(x);
  return s;
}

/// A rational as a certified number: its double (mpq_get_d truncates toward zero) and, unless
/// that is the rational exactly, the step to the next double away from zero as its error.
certified::Num certified_of(const Rational& r) {
  const double d = r.get_d();
  if (!std::isfinite(d)) throw certified::Undecided{__LINE__};
  if (r == d) return certified::constant(d);
  const double next = std::nextafter(d, r > 0 ? std::numeric_limits<double>::infinity()
                                              : -std::numeric_limits<double>::infinity());
  if (!std::isfinite(next)) throw certified::Undecided{__LINE__};
  return certified::Num{d, 0, std::fabs(next - d)};
}

/// A rational >= 0 as a certified range: its double (truncated) and the next one up.
certified::Range range_of(const Rational& r) {
  const double d = r.get_d();
  if (!std::isfinite(d)) throw certified::Undecided{__LINE__};  // beyond double (a long double)
  if (r == d) return certified::Range{d, d};
  const double up = std::nextafter(d, std::numeric_limits<double>::infinity());
  if (!std::isfinite(up)) throw certified::Undecided{__LINE__};
  return certified::Range{d, up};
}

/// 1 - x for a range x below 1 (Undecided where x may reach 1).
certified::Range one_minus(const certified::Range& x) {
  if (!(x.hi < 1)) throw certified::Undecided{__LINE__};
  return certified::widened(1 - x.hi, 1 - x.lo);
}

/// x / y for ranges, y > 0 (Undecided where y may be 0, or the quotient overflows).
certified::Range quotient(const certified::Range& x, const certified::Range& y) {
  if (!(y.lo > 0)) throw certified::Undecided{__LINE__};
  const certified::Range q = certified::widened(x.lo / y.hi, x.hi / y.lo);
  if (!std::isfinite(q.hi)) throw certified::Undecided{__LINE__};
  return q;
}

/// A rational as the nearest double, shortest digits.
std::string text(const Rational& x) {
  return protocol::format_number(x.get_d());
}

std::string text(const Vec& v, int n) {
  std::string out = "(";
  for (int i = 0; i < n; ++i) out += (i ? ", " : "") + text(v[static_cast<std::size_t>(i)]);
  return out + ")";
}

Eigen::Vector3d approx_point(const Vec& v) {
  return {v[0].get_d(), v[1].get_d(), v[2].get_d()};
}

/// |a| / b as a double ratio; 0 for 0 / 0, infinity for x / 0.
double ratio_of(const Rational& a, const Rational& b) {
  const Rational x = oracle::exact::abs(a);
  if (b == 0) return x == 0 ? 0.0 : std::numeric_limits<double>::infinity();
  return Rational(x / b).get_d();
}

/// view_axis_sign() in exact arithmetic, from the inverse of the original projection: the sign
/// of the z of its view volume's centre. Given `error` (solve_error()'s S for the original), 0
/// where a solve in T can give the other sign: the centre's z or w within its error of 0, or no
/// S (the inverse not determined in T).
int axis_sign(const Mat& original_inverse, Convention convention,
              const std::optional<std::optional<Mat>>& error) {
  const DepthRange range = clip_depth_range(convention);
  const Vec b{0, 0, Rational(range.z_low + range.z_high, 2), 1};
  const Vec centre = oracle::exact::mul(original_inverse, b);
  if (error) {
    if (!*error) return 0;
    const Vec dv = oracle::exact::mul(**error, oracle::exact::abs(b));
    if (oracle::exact::abs(centre[2]) <= dv[2] || oracle::exact::abs(centre[3]) <= dv[3]) return 0;
  }
  return (centre[2] > 0) == (centre[3] > 0) ? 1 : -1;
}

template <class T>
std::shared_ptr<const Inverse> inverse_of(const Matrix4<T>& matrix) {
  thread_local Recent<Matrix4<T>, Inverse> recent;
  return recent.get(matrix, [&] {
    Inverse out;
    out.m = oracle::exact::to_rational(matrix);
    if (!matrix.allFinite()) {
      out.inv = oracle::exact::inverse(out.m);  // (to_rational's own answer for what is not finite)
      return out;
    }
    out.inv = integer_inverse(matrix);
    return out;
  });
}

template <class T>
std::shared_ptr<const std::optional<Mat>> solve_error_of(const Matrix4<T>& matrix, int bits) {
  thread_local Recent<std::pair<Matrix4<T>, int>, std::optional<Mat>> recent;
  return recent.get({matrix, bits}, [&]() -> std::optional<Mat> {
    const std::shared_ptr<const Inverse> a = inverse_of(matrix);
    if (!a->inv) return std::nullopt;
    return solve_error<T>(a->m, *a->inv, bits);
  });
}

template <class T>
std::shared_ptr<const SolveBound> solve_bound_of(const Matrix4<T>& matrix, int bits) {
  thread_local Recent<std::pair<Matrix4<T>, int>, SolveBound> recent;
  return recent.get({matrix, bits}, [&] {
    SolveBound out;
    const std::shared_ptr<const Inverse> a = inverse_of(matrix);
    if (!a->inv) return out;
    try {
      NumMat m, inv;
      for (int i = 0; i < 4; ++i) {
        for (int j = 0; j < 4; ++j) {
          m[i][j] = certified::exactly(matrix(i, j));
          inv[i][j] = certified_of((*a->inv)[i][j]);
        }
      }
      const std::optional<NumMat> bound = solve_error_in<T, Num>(m, inv, bits);
      out.exists = bound.has_value();
      if (bound) {
        for (int i = 0; i < 4; ++i)
          for (int j = 0; j < 4; ++j) out.range[i][j] = certified::magnitude_of((*bound)[i][j]);
        out.ranged = true;
      }
      return out;
    } catch (const certified::Undecided&) {
    }
    const std::shared_ptr<const std::optional<Mat>> exact = solve_error_of(matrix, bits);
    out.exists = exact->has_value();
    if (!out.exists) return out;
    try {
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) out.range[i][j] = range_of((**exact)[i][j]);
      out.ranged = true;
    } catch (const certified::Undecided&) {
      out.ranged = false;  // beyond double's range (a long double's)
    }
    return out;
  });
}

template <class T>
int axis_sign_of(const Matrix4<T>& original, Convention convention, int bits) {
  const std::shared_ptr<const Inverse> a = inverse_of(original);
  const std::shared_ptr<const SolveBound> bound = solve_bound_of(original, bits);
  if (!bound->exists) return 0;
  if (bound->ranged) {
    // As axis_sign(): the centre's z and w against dv = S |b|, b = (0, 0, z_mid, 1), with S's
    // ranges: 0 where either is certainly within dv, the sign where both are certainly beyond.
    const DepthRange range = clip_depth_range(convention);
    const Vec b{0, 0, Rational(range.z_low + range.z_high, 2), 1};
    const Vec centre = oracle::exact::mul(*a->inv, b);
    const certified::Range z_mid = range_of(oracle::exact::abs(b[2]));
    const certified::Range one{1, 1};
    bool beyond = true, finite = true;
    for (int k : {2, 3}) {
      const certified::Range dv = bound->range[k][2] * z_mid + bound->range[k][3] * one;
      finite = finite && std::isfinite(dv.hi);  // (GMP compares with no infinity)
      if (!finite) break;
      const Rational c = oracle::exact::abs(centre[k]);
      if (c <= dv.lo) return 0;
      beyond = beyond && c > dv.hi;
    }
    if (finite && beyond) return (centre[2] > 0) == (centre[3] > 0) ? 1 : -1;
  }
  return axis_sign(*a->inv, convention, *solve_error_of(original, bits));
}

template <class T>
std::shared_ptr<const Problem<T>> problem_of(const Matrix4<T>& m, const Vector4<T>& c,
                                             Convention convention) {
  using Key = std::tuple<Matrix4<T>, Vector4<T>, Convention>;
  thread_local Recent<Key, Problem<T>> recent;
  return recent.get(Key{m, c, convention}, [&] { return Problem<T>(m, c, convention); });
}

template <class T>
std::shared_ptr<const std::optional<std::vector<Vec>>> exact_kept_region(const Matrix4<T>& m,
                                                                         const Vector4<T>& c,
                                                                         Convention convention) {
  using Key = std::tuple<Matrix4<T>, Vector4<T>, Convention>;
  thread_local Recent<Key, std::optional<std::vector<Vec>>> recent;
  return recent.get(Key{m, c, convention}, [&]() -> std::optional<std::vector<Vec>> {
    const std::shared_ptr<const Inverse> a = inverse_of(m);
    if (!a->inv) return std::nullopt;
    std::array<Vec, 8> corners;
    for (int i = 0; i < 8; ++i) {
      const std::array<int, 4> q = clip_corner(i, convention);
      Vec v = oracle::exact::mul(*a->inv, {q[0], q[1], q[2], q[3]});
      if (v[3] < 0) return std::nullopt;
      corners[static_cast<std::size_t>(i)] = v;
    }
    std::vector<Vec> out;
    for (const Vec& x : polytope::clip_volume(corners, oracle::exact::to_rational(c))) {
      if (std::find(out.begin(), out.end(), x) == out.end()) out.push_back(x);
    }
    return out;
  });
}

#define OBLIQUE_CONSUMER_JUDGING(T)                                                           \
  template std::optional<Mat> solve_error<T>(const Mat&, const Mat&, int);                    \
  template std::shared_ptr<const Inverse> inverse_of(const Matrix4<T>&);                      \
  template std::shared_ptr<const std::optional<Mat>> solve_error_of(const Matrix4<T>&, int);  \
  template std::shared_ptr<const SolveBound> solve_bound_of(const Matrix4<T>&, int);          \
  template int axis_sign_of(const Matrix4<T>&, Convention, int);                              \
  template std::shared_ptr<const Problem<T>> problem_of(const Matrix4<T>&, const Vector4<T>&, \
                                                        Convention);                          \
  template std::shared_ptr<const std::optional<std::vector<Vec>>> exact_kept_region(          \
      const Matrix4<T>&, const Vector4<T>&, Convention);
OBLIQUE_CONSUMER_JUDGING(float)
OBLIQUE_CONSUMER_JUDGING(double)
OBLIQUE_CONSUMER_JUDGING(long double)
#undef OBLIQUE_CONSUMER_JUDGING

}  // namespace oblique::oracle::consumer_judging

namespace oblique::oracle {

std::string_view not_applicable(ConsumerCheck check, cases::Family family) {
  using cases::Family;
  if (check == ConsumerCheck::corners_contain_kept && family == Family::infinite)
    return "an infinite frustum's kept region is unbounded";
  if (check == ConsumerCheck::linear_depth &&
      (family == Family::rotated || family == Family::general))
    return "its camera does not look along z";
  return "";
}

std::string describe(const ConsumerFinding& f) {
  std::string out(consumer_check_name(f.check));
  if (!f.judged) return out + ": not judged: " + f.detail;
  out += f.holds ? " holds: " : " violated: ";
  out += f.detail;
  out += " (residual / bound " + protocol::format_number(f.ratio) + ")";
  if (!f.holds && !f.likely_cause.empty()) out += "; likely cause: " + f.likely_cause;
  if (!f.holds && f.likely_cause.empty() && !f.answers_show.empty())
    out += "; likely cause: no known mistake; " + f.answers_show;
  return out;
}

}  // namespace oblique::oracle
