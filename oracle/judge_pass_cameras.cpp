// The pass-camera judges (consumers.h): the clip plane in the pass camera's space
// (camera_plane), the mirror pass's view (mirror_view, by its declared design) and the portal
// pass's view (portal_view), each against the exact answer within the rounding a correct
// computation in T may make.
#include "consumer_judging.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "oblique/oblique.h"
#include "oblique/oracle/problem.h"
#include "oblique/protocol/numbers.h"
#include "oblique/references/kept_region.h"
#include "oblique/references/pass_camera.h"

namespace oblique::oracle {

using namespace consumer_judging;

namespace {

using Lines = std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>>;

/// A square of half-size `half` in `plane` around its point nearest `near`, and the normal from
/// its centre toward the kept side; nothing for a plane without a finite normal.
Lines plane_square(const Eigen::Vector4d& plane, const Eigen::Vector3d& near, double half) {
  const Eigen::Vector3d n = plane.head<3>();
  const double nn = n.squaredNorm();
  if (!(nn > 0) || !std::isfinite(nn) || !std::isfinite(plane.w())) return {};
  const Eigen::Vector3d c = near - (n.dot(near) + plane.w()) / nn * n;
  const Eigen::Vector3d u = n.unitOrthogonal() * half, v = n.normalized().cross(u);
  const Eigen::Vector3d k[4] = {c + u + v, c - u + v, c - u - v, c + u - v};
  Lines out;
  for (int i = 0; i < 4; ++i) out.push_back({k[i], k[(i + 1) % 4]});
  out.push_back({c, c + n.normalized() * half / 2});
  return out;
}

/// A camera of `view` (world -> camera) drawn in world space: its eye, its view direction
/// (-z, `length` long) and its up (y, shorter); nothing for a singular or non-finite view.
ConsumerFinding::Drawn camera_drawn(const std::string& name, const Eigen::Matrix4d& view,
                                    double length) {
  ConsumerFinding::Drawn d;
  d.name = name;
  const Eigen::Matrix3d r = view.topLeftCorner<3, 3>();
  if (!view.allFinite() || r.determinant() == 0) return d;
  const Eigen::Matrix3d to_world = r.inverse();
  const Eigen::Vector3d eye = -to_world * view.topRightCorner<3, 1>();
  d.points = {eye};
  d.lines = {{eye, eye + length * (to_world * -Eigen::Vector3d::UnitZ()).normalized()},
             {eye, eye + 0.4 * length * (to_world * Eigen::Vector3d::UnitY()).normalized()}};
  return d;
}

Eigen::Matrix4d approx_matrix(const Mat& m) {
  Eigen::Matrix4d out;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) out(i, j) = m[i][j].get_d();
  return out;
}

}  // namespace

template <class T>
std::vector<ConsumerFinding> judge_camera_plane(const Matrix4<T>& pass_view,
                                                const Vector4<T>& world_plane,
                                                const std::vector<Vector4<T>>& surface_points,
                                                const Vector4<T>& front_point,
                                                const Vector4<T>& answer) {
  ConsumerFinding on, side;
  on.check = ConsumerCheck::plane_on_surface;
  side.check = ConsumerCheck::plane_kept_side;
  const std::shared_ptr<const Inverse> view = inverse_of(pass_view);  // the exact inverse, kept
  const Mat& w = view->m;
  const std::optional<Mat>& inv = view->inv;
  if (!inv || !answer.allFinite()) {
    on.judged = side.judged = !inv ? false : true;
    if (!inv) {
      on.detail = side.detail = "a singular view";
      return {on, side};
    }
    on.holds = side.holds = false;
    on.ratio = side.ratio = std::numeric_limits<double>::infinity();
    on.detail = side.detail = "answered " + numbers_text(answer) + ", not a finite plane";
    return {on, side};
  }
  const Mat inv_t = oracle::exact::transpose(*inv);
  const Vec world = oracle::exact::to_rational(world_plane);
  const Vec reference = oracle::exact::mul(inv_t, world);
  const Vec p = oracle::exact::to_rational(answer);
  const Rational rr = oracle::exact::dot(reference, reference);
  const Rational lambda = rr > 0 ? Rational(oracle::exact::dot(p, reference) / rr) : Rational(0);
  const Mat abs_inv_t = oracle::exact::abs(inv_t);
  const Vec chain =
      oracle::exact::mul(through_lu_bound(oracle::exact::mul(abs_inv_t, Vec{1, 1, 1, 1}),
                                          oracle::exact::transpose(w), abs_inv_t),
                         oracle::exact::abs(world));
  Vec bound;
  for (int i = 0; i < 4; ++i)
    bound[i] = oracle::exact::abs(lambda) * gamma_of<T>(oracle::tolerance::kCameraPlaneRoundings) *
                   chain[i] +
               gamma_of<T>(oracle::tolerance::kPlaneRoundings) * oracle::exact::abs(p[i]);

  double worst = 0;
  for (const Vector4<T>& x : surface_points) {
    Vec xe = oracle::exact::to_rational(x);
    // On the plane exactly: x projected onto it in rational arithmetic.
    const Rational nn = world[0] * world[0] + world[1] * world[1] + world[2] * world[2];
    const Rational off = oracle::exact::dot(world, xe) / nn;
    for (int i = 0; i < 3; ++i) xe[i] -= off * world[i] * xe[3];
    const Vec y = oracle::exact::mul(w, xe);
    const Rational value = oracle::exact::dot(p, y);
    const Rational slack = oracle::exact::dot(bound, oracle::exact::abs(y));
    const double r = ratio_of(value, slack);
    if (r > worst) {
      worst = r;
      if (oracle::exact::abs(value) > slack) {
        on.holds = false;
        on.detail = "the surface's point " + text(xe, 3) + " is at camera-space " + text(y, 3) +
                    ", where the plane " + numbers_text(answer) + " gives " + text(value) +
                    " instead of 0 (within " + text(slack) + ")";
      }
    }
  }
  on.ratio = on.holds ? std::min(worst, 1.0) : worst;
  if (on.holds)
    on.detail = "the surface's " + std::to_string(surface_points.size()) +
                " points land on the plane " + numbers_text(answer);

  const Vec y = oracle::exact::mul(w, oracle::exact::to_rational(front_point));
  const Rational value = oracle::exact::dot(p, y);
  const Rational slack = oracle::exact::dot(bound, oracle::exact::abs(y));
  side.holds = !(value < 0 && -value > slack);
  side.ratio = value >= 0 ? 0.0 : ratio_of(value, slack);
  side.detail = "a point in front of the surface, camera-space " + text(y, 3) + ", is on the " +
                (value > 0   ? "kept"
                 : value < 0 ? "clipped"
                             : "boundary") +
                " side of " + numbers_text(answer) + " (P . x = " + text(value) + ")";
  if (!on.holds || !side.holds) {
    // The pass camera's space: the camera, the surface's points and the one in front, the plane
    // as it should be and as answered, each a square around the points.
    std::vector<Eigen::Vector3d> points;
    for (const Vector4<T>& x : surface_points)
      points.push_back(approx_point(oracle::exact::mul(w, oracle::exact::to_rational(x))));
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& x : points) centre += x;
    centre /= static_cast<double>(std::max<std::size_t>(points.size(), 1));
    double half = 0;
    for (const Eigen::Vector3d& x : points) half = std::max(half, (x - centre).norm());
    if (!(half > 0) || !std::isfinite(half)) half = 1;
    const Eigen::Vector4d should(reference[0].get_d(), reference[1].get_d(), reference[2].get_d(),
                                 reference[3].get_d());
    std::vector<ConsumerFinding::Drawn> drawn = {
        {"the pass camera (eye, view direction, up)",
         {{Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, -half)},
          {Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0.4 * half, 0)}},
         {Eigen::Vector3d::Zero()}},
        {"the plane as it should be (normal toward the kept side)",
         plane_square(should, centre, half),
         {}},
        {"the plane as answered", plane_square(answer.template cast<double>(), centre, half), {}},
        {"the surface's points", {}, points},
        {"a point in front of the surface", {}, {approx_point(y)}}};
    for (ConsumerFinding* f : {&on, &side}) {
      if (f->holds) continue;
      f->drawn = drawn;
      f->drawn_space = "the pass camera's space";
    }
  }
  return {on, side};
}

namespace {

template <class T>
ConsumerFinding compare_matrix(ConsumerCheck check, const Mat& reference, const Mat& bound,
                               const Matrix4<T>& answer) {
  ConsumerFinding f;
  f.check = check;
  if (!answer.allFinite()) {
    f.holds = false;
    f.ratio = std::numeric_limits<double>::infinity();
    f.detail = "the answer is not finite";
    return f;
  }
  const Mat given = oracle::exact::to_rational(answer);
  double worst = 0;
  int wi = 0, wj = 0;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      const Rational diff = given[i][j] - reference[i][j];
      const double r = ratio_of(diff, bound[i][j]);
      if (r > worst) {
        worst = r;
        wi = i;
        wj = j;
      }
      if (oracle::exact::abs(diff) > bound[i][j]) f.holds = false;
    }
  }
  f.ratio = worst;
  auto det3 = [](const Mat& m) -> Rational {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  };
  f.detail = "entry (" + std::to_string(wi + 1) + ", " + std::to_string(wj + 1) + ") is " +
             protocol::format_number(answer(wi, wj)) + ", should be " + text(reference[wi][wj]) +
             " within " + text(bound[wi][wj]) + "; det of its 3 x 3 (the handedness) is " +
             (det3(given) < 0 ? "negative" : "positive") + ", should be " +
             (det3(reference) < 0 ? "negative" : "positive");
  return f;
}

}  // namespace

template <class T>
ConsumerFinding judge_mirror_view(const Matrix4<T>& view, const Vector4<T>& world_plane,
                                  const Matrix4<T>& answer, MirrorDesign design) {
  const Mat v = oracle::exact::to_rational(view);
  const Vec plane = oracle::exact::to_rational(world_plane);
  const Rational nn = plane[0] * plane[0] + plane[1] * plane[1] + plane[2] * plane[2];
  if (nn == 0) {
    ConsumerFinding f;
    f.check = ConsumerCheck::mirror_view;
    f.judged = false;
    f.detail = "a plane without a normal";
    return f;
  }
  Mat r{}, r_abs{};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      r[i][j] = i == j ? 1 : 0;
      r_abs[i][j] = r[i][j];
    }
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const Rational term = 2 * plane[i] * plane[j] / nn;
      r[i][j] -= term;
      r_abs[i][j] += oracle::exact::abs(term);
    }
    r[i][3] = -2 * plane[3] * plane[i] / nn;
    r_abs[i][3] = oracle::exact::abs(r[i][3]);
  }
  // The two designs: view R, and diag(-1, 1, 1, 1) view R (row 1 negated, exactly: the bound
  // is the same).
  const Mat reflected = mul(v, r);
  Mat proper = reflected;
  for (Rational& x : proper[0]) x = -x;
  const bool proper_declared = design == MirrorDesign::proper_camera;
  const Mat& reference = proper_declared ? proper : reflected;
  Mat bound = mul(oracle::exact::abs(v), r_abs);
  const Rational g = gamma_of<T>(oracle::tolerance::kPassViewRoundings);
  for (auto& row : bound) {
    for (auto& x : row) x *= g;
  }
  // A pass camera built as a camera (a look-at of the reflected eye: normalised axes, cross
  // products) errs relative to its rows, not to each entry: an entry that is 1e-19 exactly may
  // come out 0. So each entry of the 3 x 3 block is held within its row's largest bound, and the
  // translation, t_i = -row_i . eye, within that times |eye|_1 more (eye: the pass camera's
  // position, exact). What a point at unit distance sees is the same either way.
  const std::optional<Mat> to_world = oracle::exact::inverse(reference);
  Rational eye_size = 0;
  if (to_world) {
    for (int k = 0; k < 3; ++k) eye_size += oracle::exact::abs((*to_world)[k][3]);
  }
  for (auto& row : bound) {
    const Rational largest = std::max({row[0], row[1], row[2]});
    for (int j = 0; j < 3; ++j) row[j] = largest;
    row[3] += largest * eye_size;
  }
  ConsumerFinding f = compare_matrix(ConsumerCheck::mirror_view, reference, bound, answer);
  if (f.holds) {
    f.detail = std::string("the ") + (proper_declared ? "proper_camera" : "reflected_view") +
               " design's matrix (" + (proper_declared ? "diag(-1, 1, 1, 1) view R" : "view R") +
               "), " + f.detail;
  } else if (answer.allFinite() &&
             compare_matrix(ConsumerCheck::mirror_view, proper_declared ? reflected : proper, bound,
                            answer)
                 .holds) {
    // The other design: named as such, not as a broken mirror.
    f.detail =
        proper_declared
            ? "the answer is the reflected_view design, view R (an improper camera, det < 0), "
              "while the proper_camera design is declared (diag(-1, 1, 1, 1) view R, the flip done "
              "in the projection or the texture): with both, the image is flipped twice. " +
                  f.detail
            : "the answer is the proper_camera design, diag(-1, 1, 1, 1) view R (a proper camera, "
              "det > 0, looking at the reflected scene), not the reflected view R: right only "
              "when the horizontal flip is done in the projection or the texture lookup; if it "
              "is, declare the design (Consumers::mirror_design = MirrorDesign::proper_camera; "
              "verify --mirror-design proper_camera). " +
                  f.detail;
  }
  if (!f.holds) {
    const Eigen::Matrix4d main_view = view.template cast<double>();
    const ConsumerFinding::Drawn main = camera_drawn("the main camera", main_view, 1);
    const Eigen::Vector4d mirror = world_plane.template cast<double>();
    const Eigen::Vector3d eye = main.points.empty() ? Eigen::Vector3d::Zero() : main.points[0];
    const double distance =
        std::abs(mirror.head<3>().dot(eye) + mirror.w()) / mirror.head<3>().norm();
    const double length = std::isfinite(distance) && distance > 0 ? distance : 1;
    f.drawn = {
        camera_drawn("the main camera", main_view, length),
        camera_drawn("the mirror pass's camera as it should be", approx_matrix(reference), length),
        camera_drawn("the mirror pass's camera as answered", answer.template cast<double>(),
                     length),
        {"the mirror (normal toward its front)", plane_square(mirror, eye, length), {}}};
    f.drawn_space = "world space";
  }
  return f;
}

template <class T>
ConsumerFinding judge_portal_view(const Matrix4<T>& view, const Matrix4<T>& frame,
                                  const Matrix4<T>& linked, const Matrix4<T>& answer) {
  const std::shared_ptr<const Inverse> linked_exactly = inverse_of(linked);
  const Mat& l = linked_exactly->m;
  const std::optional<Mat>& l_inv = linked_exactly->inv;
  if (!l_inv) {
    ConsumerFinding f;
    f.check = ConsumerCheck::portal_view;
    f.judged = false;
    f.detail = "a singular portal frame";
    return f;
  }
  Mat turn{};
  turn[0][0] = -1;
  turn[1][1] = 1;
  turn[2][2] = -1;
  turn[3][3] = 1;
  const Mat v = oracle::exact::to_rational(view), fr = oracle::exact::to_rational(frame);
  const Mat reference = mul(mul(mul(v, fr), turn), *l_inv);
  // |v| |fr| |l^-1| lu_bound(l) |l^-1| = 32 max|l| (|v| |fr| |l^-1| 1)(1^T |l^-1|), as
  // through_lu_bound() has it: matrix-vector products only.
  const Mat abs_l_inv = oracle::exact::abs(*l_inv);
  const Vec rows = oracle::exact::mul(
      oracle::exact::abs(v),
      oracle::exact::mul(oracle::exact::abs(fr), oracle::exact::mul(abs_l_inv, Vec{1, 1, 1, 1})));
  Mat bound = through_lu_bound(rows, l, abs_l_inv);
  const Rational g = gamma_of<T>(oracle::tolerance::kPassViewRoundings);
  for (auto& row : bound)
    for (auto& x : row) x *= g;
  ConsumerFinding f = compare_matrix(ConsumerCheck::portal_view, reference, bound, answer);
  if (!f.holds) {
    const Eigen::Matrix4d main_view = view.template cast<double>();
    const Eigen::Matrix4d here = frame.template cast<double>(),
                          there = linked.template cast<double>();
    const ConsumerFinding::Drawn main = camera_drawn("the main camera", main_view, 1);
    const Eigen::Vector3d eye = main.points.empty() ? Eigen::Vector3d::Zero() : main.points[0];
    const double distance = (here.col(3).head<3>() - eye).norm();
    const double length = std::isfinite(distance) && distance > 0 ? distance : 1;
    auto portal = [](const Eigen::Matrix4d& fr) {
      return plane_square(
          plane_from_normal_and_point<double>(fr.block<3, 1>(0, 2), fr.block<3, 1>(0, 3)),
          fr.block<3, 1>(0, 3), 1);
    };
    f.drawn = {
        camera_drawn("the main camera", main_view, length),
        camera_drawn("the portal pass's camera as it should be", approx_matrix(reference), length),
        camera_drawn("the portal pass's camera as answered", answer.template cast<double>(),
                     length),
        {"this portal (normal toward its front)", portal(here), {}},
        {"the linked portal", portal(there), {}}};
    f.drawn_space = "world space";
  }
  return f;
}

#define OBLIQUE_PASS_CAMERA_JUDGES(T)                                                             \
  template std::vector<ConsumerFinding> judge_camera_plane(const Matrix4<T>&, const Vector4<T>&,  \
                                                           const std::vector<Vector4<T>>&,        \
                                                           const Vector4<T>&, const Vector4<T>&); \
  template ConsumerFinding judge_mirror_view(const Matrix4<T>&, const Vector4<T>&,                \
                                             const Matrix4<T>&, MirrorDesign);                    \
  template ConsumerFinding judge_portal_view(const Matrix4<T>&, const Matrix4<T>&,                \
                                             const Matrix4<T>&, const Matrix4<T>&);
OBLIQUE_PASS_CAMERA_JUDGES(float)
OBLIQUE_PASS_CAMERA_JUDGES(double)
OBLIQUE_PASS_CAMERA_JUDGES(long double)
#undef OBLIQUE_PASS_CAMERA_JUDGES

}  // namespace oblique::oracle
