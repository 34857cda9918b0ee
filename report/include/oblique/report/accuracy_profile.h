// The accuracy profile of an implementation: for each answer that passes the properties, the
// error of each entry of row 3 against the exact answer (in ulps of the answer's type, and bits
// lost), grouped by family, hard place and the stiffness kappa of the case; its time per answer;
// and the core's closed form, general and accurate methods measured on the same cases in the
// same run. `oblique verify --accuracy DIR`, oblique::testing's profile_accuracy() and
// `oblique report accuracy --impl` write it with write_profile_report().
#pragma once

#include <chrono>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "oblique/client/program.h"
#include "oblique/depth_convention.h"
#include "oblique/plane.h"
#include "oblique/status.h"

namespace oblique::oracle {
template <class T>
class Problem;
}

namespace oblique::report {

class ReportFiles;

/// One answer's error: each entry of row 3 against the exact answer.
struct ProfiledAnswer {
  std::string family, place;
  Convention convention = Convention::gl;
  /// The condition number of C . Q (oblique/oracle/tolerance.h): how stiff the case is.
  double kappa = 0;
  /// How far M'_3i is from the correctly rounded exact entry, in ulps of the row: the ulp, in
  /// the answer's type, of the row's largest exact entry. A plane's coefficients go together (an
  /// entry that is exactly 0 has no ulp of its own), so a small entry's error counts on the
  /// row's scale; for the largest entry this is oracle::exact::ulp_distance. Infinity for an entry
  /// that is not finite.
  double ulps[4] = {0, 0, 0, 0};
  std::string request;  ///< the case as a request line (JSON), for the replay

  double worst_ulps() const;
};

/// bits lost = log2(ulps + 1): 0 for the correctly rounded answer.
double bits_lost(double ulps);

/// How a profile's time per answer was measured.
enum class Timing {
  none,        ///< not measured
  in_process,  ///< the function called in this process (ns per call)
  round_trip,  ///< requests sent over the pipe and the answers read back (ns per request)
};

struct Profile {
  std::string name;    ///< the implementation, or the core's method ("core closed_form", ...)
  std::string scalar;  ///< float, double or long double
  bool core = false;   ///< one of the core's methods, measured beside the implementation
  Timing timing = Timing::none;
  double ns = std::numeric_limits<double>::quiet_NaN();  ///< per answer, as `timing` says
  std::vector<ProfiledAnswer> answers;
  long refused = 0;  ///< cases with an answer that it answered with a status
};

/// The error of `answer` (status ok) to the case of `problem`, whose exact status is ok.
/// Compiled for float, double and long double.
template <class T>
ProfiledAnswer profile_answer(const oracle::Problem<T>& problem, const Matrix4<T>& answer);

/// One case, as the core's methods are asked it.
template <class T>
struct ProfileInput {
  Matrix4<T> matrix;
  Vector4<T> plane;
  Convention convention = Convention::gl;
  std::string family, place, request;
};

/// Adds one answer to `profile`, to the case of `problem` (its exact status ok) asked as
/// `input`: a status is counted as refused, a matrix profiled (profile_answer()) with the input's
/// family, place and request. Compiled for float, double and long double.
template <class T>
void record_answer(Profile& profile, const oracle::Problem<T>& problem,
                   const ProfileInput<T>& input, Status status, const Matrix4<T>& projection);

/// The core's closed form (on the inputs of the standard perspective shape), general and
/// accurate methods on `inputs`, in T, in this process: each one's errors and ns per call.
template <class T>
std::vector<Profile> core_profiles(const std::vector<ProfileInput<T>>& inputs);

/// The time per call of `call(i)` over i in [0, count): passes over every i repeated until they
/// take 0.1 s, the median of 5 such measurements, in ns per call.
double ns_per_call(std::size_t count, const std::function<void(std::size_t)>& call);

/// A program's time per request over the pipe: `requests` sent at once to `program` and timed
/// to the last answer (JSON both ways, the pipe and the program's own work). A program that is
/// not running yet is started and answers the first request before the clock starts: its start
/// is no request's time. `ns` is NaN unless every request got its answer (`failure` says why
/// not); the answers are in `lines`.
struct RoundTrip {
  std::optional<client::Failure> failure;
  double ns = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::string> lines;
};
RoundTrip time_round_trip(client::Program& program, const std::vector<std::string>& requests);

/// Which of the points (ns, bits lost) are on the error-against-time front: no other point is
/// as fast and as accurate and better in one. NaN points are on no front.
std::vector<bool> non_dominated(const std::vector<std::pair<double, double>>& points);

/// The palette of the accuracy charts: one colour a method, the same in every chart.
const char* chart_colour(std::size_t index);

/// One point of an error-against-time chart.
struct TimePoint {
  std::string label;                                            ///< in the key
  double ns = 0;                                                ///< time per answer
  double worst_bits = 0;                                        ///< filled
  double p999_bits = std::numeric_limits<double>::quiet_NaN();  ///< open; NaN: none
  std::size_t colour = 0;                                       ///< chart_colour()
  int point_type = 7;                                           ///< gnuplot's pt
};

/// Stages the error-against-time chart in `files`: STEM.gp, STEM_points.dat, STEM_front.dat
/// (the non_dominated() points as steps) and, with gnuplot, STEM.png, the points named in the
/// key below it (no labels on the chart to overlap). Whether the PNG was drawn.
bool stage_time_chart(ReportFiles& files, const std::string& stem, const std::string& title,
                      const std::string& xlabel, const std::vector<TimePoint>& points);

struct ProfileReportOptions {
  std::filesystem::path dir;
  std::string title;  ///< the report's first line, e.g. "example_correct (double) over the pipe"
  int worst = 10;     ///< the implementation's worst answers kept, each with its replay
  /// The replay command of one of the implementation's answers, kept at `json` (its request and
  /// error); empty: the report gives the inputs alone.
  std::function<std::string(const ProfiledAnswer&, const std::string& json)> replay;
};

/// Writes, all or nothing, in options.dir: accuracy.md (the profiles side by side: worst, 99.9th
/// percentile and mean error in bits, time; by family, place and kappa's decade; the worst
/// answers with their replays), accuracy.csv (one row per profile and group), worst-K.json (the
/// worst answers' cases, for `oblique verify --replay`), and the charts accuracy.png (error
/// against time, one colour per method, the non-dominated front) and stiffness.png (error
/// against kappa) with gnuplot. The first profile is the implementation's. The paths written,
/// or nullopt (why on `log`, the folder's earlier files kept).
std::optional<std::vector<std::filesystem::path>> write_profile_report(
    const std::vector<Profile>& profiles, const ProfileReportOptions& options, std::ostream& log);

}  // namespace oblique::report
