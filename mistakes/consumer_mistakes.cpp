// The consumer mistakes (consumer_mistakes.h): their words, each as a wrong function, and the
// diagnosis of a consumer finding by asking each wrong function of the finding's kind the same
// inputs.
#include "oblique/mistakes/consumer_mistakes.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "oblique/references/depth_reconstruction.h"
#include "oblique/references/frustum_planes.h"
#include "oblique/references/kept_region.h"
#include "oblique/references/pass_camera.h"

namespace oblique::mistakes {

namespace {

using protocol::ConsumerKind;

// clang-format off
constexpr ConsumerMistakeEntry kConsumerCatalogue[] = {
    {ConsumerMistake::reconstructs_with_original, ConsumerKind::view_position,
     "reconstructs_with_original", "the depth decompressed with the camera's unmodified matrix",
     "The pixel's depth was written through the oblique M', but the answers are M's: code that "
     "inverts the camera's own projection M (the one it keeps for the main view), or that takes "
     "view z from M's near and far (a perspectiveDepthToViewZ-style helper) and the ray from "
     "rows 1 and 2, gives them. The two matrices share rows 1, 2 and 4 only: the depth maps to "
     "another point on the pixel's ray, nearer or farther than the surface (Unity "
     "Graphics#3919, three.js#21403, ioq3#641).",
     "Reconstruct with the matrix the depth was rendered with: M'^-1 (x, y, z_ndc, 1), divided "
     "by w.",
     "your answers are a reconstruction with the camera's own projection M: each pixel's depth placed as if the near plane had not moved"},
    {ConsumerMistake::ndc_depth_of_other_convention, ConsumerKind::view_position,
     "ndc_depth_of_other_convention", "the window depth mapped to NDC by the other convention",
     "The code maps the stored depth d to NDC z as the other depth convention does: z = 2 d - 1 "
     "on a [0, 1] (or reversed-Z) buffer, z = d on an OpenGL [-1, 1] one. Every pixel lands at "
     "another depth on its ray.",
     "z_ndc = 2 d - 1 for [-1, 1] depth and z_ndc = d for [0, 1] and reversed-Z depth, from the "
     "matrix's convention.",
     "your answers place each depth as the other depth convention would: every point lands at another depth on its pixel's ray"},
    {ConsumerMistake::reads_reversed_as_forward, ConsumerKind::view_position,
     "reads_reversed_as_forward", "a reversed-Z depth turned forward before the inverse",
     "On a reversed-Z buffer the code flips the stored depth, 1 - d, as a linearisation written "
     "for forward depth needs, but then applies M'^-1, which already maps reversed depth: the "
     "near and far ends of every ray trade places.",
     "Give M'^-1 the depth as stored (z_ndc = d on reversed Z); flip only for code that reads "
     "forward depth.",
     "your answers trade the near and far ends of each pixel's ray: a reversed-Z depth read as forward depth"},
    {ConsumerMistake::reads_v_the_other_way, ConsumerKind::view_position,
     "reads_v_the_other_way", "the pixel's v read the other way up",
     "The code maps the pixel's texture coordinate to NDC as an API whose v runs the other way "
     "does: uv * 2 - 1 on a top-down (Direct3D, Metal) coordinate, or 1 - 2 v on one that runs "
     "with NDC y (OpenGL, Vulkan). Each pixel is reconstructed on the ray of the pixel mirrored "
     "in y; only the middle row is right.",
     "NDC y = 2 v - 1 where v runs with NDC y, 1 - 2 v where it runs against it; declare which "
     "(--uv-v) and test both.",
     "your answers are those of the pixel mirrored in y: the texture coordinate's v read the "
     "other way up"},
    {ConsumerMistake::ignores_oblique_row, ConsumerKind::view_position, "ignores_oblique_row",
     "the depth solved from the projection's z entries alone",
     "The code solves view z from M'33, M'34 and M'43 (z_ndc = (M'33 z + M'34) / (M'43 z)) and x "
     "and y by dividing by M'11 and M'22, the fast path for an ordinary perspective matrix. The "
     "oblique row has x and y entries too (M'31, M'32): the depth of a tilted near plane is "
     "read as that of an untilted one.",
     "Reconstruct with the whole inverse, M'^-1 (x, y, z_ndc, 1) / w, or solve with M'31 and "
     "M'32 included.",
     "your answers are those of a matrix without the oblique tilt: M'31 and M'32 ignored"},
    {ConsumerMistake::transposed_matrix, ConsumerKind::view_position, "transposed_matrix",
     "the inverse projection used transposed",
     "The code multiplies by the transpose of the matrix it was handed: a column-vector product "
     "(M v, mul(M, v)) on a matrix stored for row vectors (v M, DirectXMath and D3DX style), or "
     "the other way round. Every coordinate of the reconstructed point mixes the wrong entries.",
     "Multiply as the matrix is stored: mul(v, M) for row vectors, mul(M, v) for column vectors; "
     "declare the engine's layout (--vectors row) so that it is handed what its uniforms hold.",
     "your answers are those of the transposed matrix: the matrix read in the other layout (row "
     "vectors for column vectors)"},
    {ConsumerMistake::linearises_with_near_far, ConsumerKind::linear_depth,
     "linearises_with_near_far", "linear depth from the near and far planes (zparams)",
     "The code linearises with the textbook n f / (f - d (f - n)), n and f read off the "
     "unmodified perspective matrix in its convention (a _ZBufferParams-style shortcut; d "
     "turned forward, 1 - d, on reversed Z). The oblique M' has no "
     "near and far planes at n and f: its depth is a function of the tilted plane, so the "
     "linear depth is wrong everywhere the near plane moved.",
     "Linearise with the matrix the depth was rendered with: the view position M'^-1 (x, y, "
     "z_ndc, 1) / w, its distance along the view axis.",
     "your linear depths are those of the camera's own near and far planes: depth linearised as if the near plane had not moved"},
    {ConsumerMistake::world_with_original, ConsumerKind::world_position, "world_with_original",
     "the world position through the camera's unmodified view-projection",
     "The code reconstructs the world position through the inverse of M V, the view-projection "
     "the camera keeps for its main view (an inverse view-projection uniform set once per "
     "camera), while the pixel's depth was written through the oblique M' V of the mirror or "
     "portal pass: the depth maps to another point on the pixel's ray.",
     "Invert the view-projection the pass rendered with, (M' V)^-1, and set it per pass.",
     "your world positions are reconstructed with the camera's own projection M: each pixel's "
     "depth placed as if the near plane had not moved"},
    {ConsumerMistake::world_through_view, ConsumerKind::world_position, "world_through_view",
     "the view position carried by the view matrix, not its inverse",
     "The code reconstructs the view position right and then multiplies it by the view matrix V "
     "(world to camera) where the inverse view V^-1 (camera to world) belongs: the point is "
     "carried away from the world a second time.",
     "World = V^-1 (view position, 1): the inverse view (camera to world), or the inverse "
     "view-projection applied to the pixel's NDC.",
     "your answers are the view position carried by the view matrix (world to camera), not by "
     "its inverse"},
    {ConsumerMistake::gl_planes_on_any_matrix, ConsumerKind::culling_planes,
     "gl_planes_on_any_matrix", "OpenGL's culling rows on a matrix of another convention",
     "The code extracts the near and far culling planes as OpenGL does (near = M'_4 + M'_3, far "
     "= M'_4 - M'_3) whatever the matrix's depth convention. On a [0, 1] or reversed-Z oblique "
     "matrix the near plane is then not C, and the far plane not the one the rasterizer clips "
     "at: objects are culled that are drawn, or drawn that are culled.",
     "Near = M'_4 + M'_3, far = M'_4 - M'_3 for [-1, 1]; near = M'_3, far = M'_4 - M'_3 for "
     "[0, 1]; near = M'_4 - M'_3, far = M'_3 for reversed Z.",
     "your near and far planes are OpenGL's rows on a matrix of another depth convention"},
    {ConsumerMistake::planes_of_transpose, ConsumerKind::culling_planes, "planes_of_transpose",
     "the culling planes of the transposed matrix",
     "The code extracts the planes from columns instead of rows (a row-major array read as "
     "column-major, or the other way round): the planes of M'^T, which bound nothing the camera "
     "sees.",
     "Combine the rows of M': left = M'_4 + M'_1, right = M'_4 - M'_1, and so on.",
     "your planes are those of the transposed matrix: the matrix read in the other layout"},
    {ConsumerMistake::plane_without_translation, ConsumerKind::camera_plane,
     "plane_without_translation", "the plane's normal rotated, its distance kept",
     "The code rotates the world plane's normal into the pass camera's space but keeps its "
     "distance C_w from world space (three.js#16013, drei#721). Only a camera at the world's "
     "origin sees the plane there; elsewhere the clip plane is moved off the surface.",
     "Transform the plane by the inverse transpose of the view matrix: C_camera = W^-T C_world "
     "(for a rigid W: n' = R n, d' = d - n' . t).",
     "your plane has the right normal but the world plane's distance: it is moved off the surface"},
    {ConsumerMistake::plane_flipped_for_mirrors, ConsumerKind::camera_plane,
     "plane_flipped_for_mirrors", "the camera-space plane negated again for a mirrored view",
     "The code negates the transformed plane when the pass view mirrors (det < 0), reasoning that "
     "the reflection turns the plane around. The inverse transpose already has: the plane now "
     "keeps the side behind the mirror, and the pass draws what it should clip.",
     "C_camera = W^-T C_world for every pass view, mirrored or not.",
     "your plane keeps the wrong side where the pass view mirrors"},
    {ConsumerMistake::plane_through_view, ConsumerKind::camera_plane, "plane_through_view",
     "the plane transformed like a point, W C instead of W^-T C",
     "The code multiplies the world plane by the view matrix as if it were a point or a "
     "direction. Planes transform by the inverse transpose: W C is another plane whenever W is "
     "not a pure rotation.",
     "C_camera = W^-T C_world.",
     "your plane is the world plane transformed as a point is, not as a plane"},
    {ConsumerMistake::mirror_by_reflected_look_at, ConsumerKind::mirror_view,
     "mirror_by_reflected_look_at", "a look-at view of the reflected eye",
     "The code reflects the eye, the view direction and up through the mirror and builds a "
     "look-at view from them: a proper rotation, not a reflection. The image is the mirror's "
     "seen unmirrored (left and right swapped against a real mirror) unless the projection or "
     "the texture lookup flips it, and the winding is not flipped either.",
     "View = main view * R, with R the reflection through the mirror's plane (det -1), and flip "
     "the winding; or keep a proper camera and flip x in the projection or the lookup, and say "
     "so (--mirror-design).",
     "your mirror view is a proper rotation: the reflected scene seen unmirrored"},
    {ConsumerMistake::portal_without_turn, ConsumerKind::portal_view, "portal_without_turn",
     "the portal view without the half turn",
     "The code composes view * frame * linked^-1, leaving out the half turn about up between "
     "the two portals. What is in front of the linked portal is then seen behind this one, "
     "mirrored through the wall.",
     "View = main view * frame * turn * linked^-1 with turn = diag(-1, 1, -1, 1).",
     "your portal view looks out of the linked portal's back"},
    {ConsumerMistake::corners_of_oblique_matrix, ConsumerKind::corners,
     "corners_of_oblique_matrix", "the oblique matrix's eight corners as the drawn volume",
     "The code bounds what the oblique pass draws by M'^-1's eight clip-space corners divided by "
     "w, as for an ordinary camera (cascade fitting, light lists: Godot#89140, Ogre#1337). Where "
     "C cuts an edge of the view volume behind the eye, a corner lands behind the camera and "
     "their hull misses part of the region the pass draws.",
     "Bound the original view volume cut by C: the vertices of its part on C's kept side "
     "(kept_region_vertices()).",
     "your corners are the oblique matrix's eight corners, some behind the camera"},
};
// clang-format on

/// Whether `a` is `b` to half of T's digits: each group of `group` numbers alike (scaled to its
/// largest magnitude, or, for planes, normalised by the norm of their first three), the groups in
/// order or, `any_order`, matched in any order.
template <class T>
bool alike(const std::vector<T>& a, const std::vector<T>& b, std::size_t group, bool planes,
           bool any_order) {
  if (a.size() != b.size() || group == 0 || a.size() % group != 0) return false;
  const T tolerance = T(8) * std::sqrt(std::numeric_limits<T>::epsilon());
  // An answer that is not finite is a formula's where that formula gives NaN and infinities in
  // the same places (n f / (f - d (f - n)) at an infinite f: inf / inf; a divide by a w that is 0,
  // whose sign, and so the infinities', is rounding's: either sign), and the same finite numbers
  // elsewhere.
  bool finite = true;
  for (std::size_t i = 0; i < a.size(); ++i)
    finite = finite && std::isfinite(a[i]) && std::isfinite(b[i]);
  if (!finite) {
    for (std::size_t i = 0; i < a.size(); ++i) {
      const bool same =
          (std::isnan(a[i]) && std::isnan(b[i])) || (std::isinf(a[i]) && std::isinf(b[i])) ||
          a[i] == b[i] ||
          (std::isfinite(a[i]) && std::isfinite(b[i]) &&
           std::abs(a[i] - b[i]) <= tolerance * std::max(std::abs(a[i]), std::abs(b[i])));
      if (!same) return false;
    }
    return true;
  }
  auto normalised = [group, planes](const std::vector<T>& v, std::size_t at) {
    std::vector<T> out(v.begin() + static_cast<long>(at),
                       v.begin() + static_cast<long>(at + group));
    T scale = 0;
    for (std::size_t k = 0; k < (planes ? 3 : group); ++k) scale += out[k] * out[k];
    scale = std::sqrt(scale);
    if (!planes || scale == 0) {
      scale = 0;
      for (T x : out) scale = std::max(scale, std::abs(x));
    }
    if (scale > 0 && planes)
      for (T& x : out) x /= scale;
    return std::make_pair(out, scale);
  };
  auto group_alike = [&](std::size_t i, std::size_t j) {
    const auto [x, sx] = normalised(a, i);
    const auto [y, sy] = normalised(b, j);
    const T scale = planes ? T(1) : std::max({sx, sy, T(1e-30)});
    for (std::size_t k = 0; k < group; ++k) {
      if (std::abs(x[k] - y[k]) > tolerance * scale) return false;
    }
    return true;
  };
  const std::size_t groups = a.size() / group;
  if (!any_order) {
    for (std::size_t g = 0; g < groups; ++g) {
      if (!group_alike(g * group, g * group)) return false;
    }
    return true;
  }
  std::vector<bool> used(groups, false);
  for (std::size_t g = 0; g < groups; ++g) {
    bool found = false;
    for (std::size_t h = 0; h < groups && !found; ++h) {
      if (!used[h] && group_alike(g * group, h * group)) used[h] = found = true;
    }
    if (!found) return false;
  }
  return true;
}

/// alike() with the grouping of `kind`'s answer.
template <class T>
bool alike_answers(ConsumerKind kind, const std::vector<T>& a, const std::vector<T>& b) {
  switch (kind) {
    case ConsumerKind::view_position:
    case ConsumerKind::world_position: return alike(a, b, 3, false, false);
    case ConsumerKind::linear_depth: return alike(a, b, 1, false, false);
    case ConsumerKind::culling_planes:
    case ConsumerKind::camera_plane: return alike(a, b, 4, true, false);
    case ConsumerKind::mirror_view:
    case ConsumerKind::portal_view: return alike(a, b, 16, false, false);
    case ConsumerKind::corners: return alike(a, b, 3, false, true);
  }
  return false;
}

/// A number for the words (6 significant digits; the report's inputs carry the exact ones).
std::string short_number(long double x) {
  std::ostringstream out;
  out.precision(6);
  out << static_cast<double>(x);
  return out.str();
}

/// What a view position answer shows against the sample it answered: where it projects under
/// M' (on the pixel's ray or off it, by how many pixels, mirrored in y) and how far along.
template <class T>
std::string view_position_shows(const oracle::DepthSample<T>& s, const std::vector<T>& answer,
                                const std::vector<T>& right) {
  using Wide = long double;
  const Vector4<Wide> a(answer[0], answer[1], answer[2], 1);
  const Vector4<Wide> clip = s.projection.template cast<Wide>() * a;
  if (!std::isfinite(clip.w()) || clip.w() <= 0)
    return "the answer projects to no pixel under M' (it is behind the eye, at it, or not "
           "finite)";
  const Wide x = clip.x() / clip.w(), y = clip.y() / clip.w(), z = clip.z() / clip.w();
  const Wide window = s.convention == Convention::gl ? (z + 1) / 2 : z;
  const Wide nx = s.ndc_x, ny = s.ndc_y;
  // Pixels of the sample's target (NDC spans 2 over its width), or of a 1920 x 1080 one.
  const Wide width = s.pixel.width > 0 ? s.pixel.width : 1920;
  const Wide height = s.pixel.height > 0 ? s.pixel.height : 1080;
  const Wide dx = (x - nx) * width / 2, dy = (y - ny) * height / 2;
  const Wide close = 0.01L;  // of a pixel
  const Wide right_distance =
      std::hypot(std::hypot(Wide(right[0]), Wide(right[1])), Wide(right[2]));
  const Wide distance = std::hypot(std::hypot(a.x(), a.y()), a.z());
  const std::string along =
      right_distance > 0
          ? short_number(distance / right_distance) +
                " times as far from the eye as the point the stored depth stands for (window "
                "depth " +
                short_number(window) + " under M', where the buffer holds " +
                short_number(s.depth) + ")"
          : "at window depth " + short_number(window) + " under M'";
  if (std::fabs(dx) <= close && std::fabs(dy) <= close)
    return "the answer is on the pixel's ray, " + along;
  const Wide my = (y + ny) * height / 2;
  if (std::fabs(dx) <= close && std::fabs(my) <= close && std::fabs(dy) > 1)
    return "the answer is on the ray of the pixel mirrored in y (NDC y " + short_number(y) +
           " for " + short_number(ny) + "), " + along;
  return "the answer is off the pixel's ray: it projects (" + short_number(dx) + ", " +
         short_number(dy) + ") pixels from the pixel's centre (NDC (" + short_number(x) + ", " +
         short_number(y) + ") for (" + short_number(nx) + ", " + short_number(ny) + ") on a " +
         short_number(width) + " x " + short_number(height) + " target), " + along;
}

/// The sample a depth ask is about (none for the other kinds).
template <class T>
std::optional<oracle::DepthSample<T>> sample_of(const oracle::ConsumerAsk<T>& ask) {
  std::optional<oracle::DepthSample<T>> sample;
  Consumers<T> recording;
  recording.view_position = recording.world_position = [&sample](const oracle::DepthSample<T>& s) {
    sample = s;
    return Vector3<T>::Zero().eval();
  };
  recording.linear_depth = [&sample](const oracle::DepthSample<T>& s) {
    sample = s;
    return T(0);
  };
  try {
    (void)ask.call(recording);
  } catch (...) {
  }
  return sample;
}

/// A world position carried into the pass camera's space (view (p, 1)), where the pixel's ray is.
template <class T>
std::vector<T> in_pass_camera(const Matrix4<T>& view, const std::vector<T>& p) {
  if (p.size() != 3) return p;
  const Vector4<long double> v =
      view.template cast<long double>() * Vector4<long double>(p[0], p[1], p[2], 1.0L);
  return {static_cast<T>(v.x()), static_cast<T>(v.y()), static_cast<T>(v.z())};
}

/// What a violated answer shows, in words: for the depth kinds where it lies against the pixel's
/// ray; for the others how far it is from the core's reference answer.
template <class T>
std::string answers_show(const oracle::ConsumerAsk<T>& ask, const std::vector<T>& answer) {
  std::vector<T> right;
  try {
    right = ask.call(oracle::reference_consumers<T>());
  } catch (...) {
    return "";
  }
  for (const T x : answer)
    if (!std::isfinite(x)) return "the answer is not finite (NaN or infinity)";
  if (right.size() != answer.size()) return "";
  if (ask.kind == ConsumerKind::view_position || ask.kind == ConsumerKind::world_position) {
    if (const auto sample = sample_of(ask)) {
      if (ask.kind == ConsumerKind::view_position)
        return view_position_shows(*sample, answer, right);
      return "in the pass camera's space (the answer times its view), " +
             view_position_shows(*sample, in_pass_camera(sample->view, answer),
                                 in_pass_camera(sample->view, right));
    }
  }
  if (ask.kind == ConsumerKind::linear_depth) {
    const long double r = right[0], a = answer[0];
    if (r == 0) return "the answer is " + short_number(a) + " where the right linear depth is 0";
    return "the answer is " + short_number(a / r) + " times the right linear depth (" +
           short_number(a) + " for " + short_number(r) + ")";
  }
  long double largest = 0, scale = 0;
  std::size_t at = 0;
  for (std::size_t i = 0; i < answer.size(); ++i) {
    const long double d = std::fabs(static_cast<long double>(answer[i]) - right[i]);
    scale = std::max(scale, std::fabs(static_cast<long double>(right[i])));
    if (d > largest) {
      largest = d;
      at = i;
    }
  }
  return "the answer differs from the core's reference answer most in its number " +
         std::to_string(at + 1) + " of " + std::to_string(answer.size()) + ", by " +
         short_number(largest) +
         (scale > 0 ? " (" + short_number(largest / scale) + " of the largest reference number)"
                    : "");
}

}  // namespace

const ConsumerMistakeEntry& consumer_mistake_entry(ConsumerMistake mistake) {
  for (const ConsumerMistakeEntry& e : kConsumerCatalogue) {
    if (e.mistake == mistake) return e;
  }
  throw std::logic_error("a consumer mistake without a catalogue entry");
}

std::optional<ConsumerMistake> parse_consumer_mistake(std::string_view name) {
  for (const ConsumerMistakeEntry& e : kConsumerCatalogue) {
    if (e.name == name) return e.mistake;
  }
  return std::nullopt;
}

template <class T>
Consumers<T> mistaken_consumers(ConsumerMistake mistake) {
  Consumers<T> c;
  c.name = "mistake_" + std::string(consumer_mistake_entry(mistake).name);
  switch (mistake) {
    case ConsumerMistake::reconstructs_with_original:
      c.view_position = [](const oracle::DepthSample<T>& s) {
        return view_position(s.original, s.ndc_x, s.ndc_y, s.depth, s.convention);
      };
      break;
    case ConsumerMistake::ndc_depth_of_other_convention:
      c.view_position = [](const oracle::DepthSample<T>& s) {
        // view_position() maps d by `convention`: the other one's mapping, on the same rows
        const T z = s.convention == Convention::gl ? s.depth : T(2) * s.depth - T(1);
        const Vector4<T> v = s.projection.inverse() * Vector4<T>(s.ndc_x, s.ndc_y, z, T(1));
        return Vector3<T>(v.template head<3>() / v.w());
      };
      break;
    case ConsumerMistake::reads_reversed_as_forward:
      c.view_position = [](const oracle::DepthSample<T>& s) {
        const T d = s.convention == Convention::reversed_z ? T(1) - s.depth : s.depth;
        return view_position(s.projection, s.ndc_x, s.ndc_y, d, s.convention);
      };
      break;
    case ConsumerMistake::reads_v_the_other_way:
      c.view_position = [](const oracle::DepthSample<T>& s) {
        return view_position(s.projection, s.ndc_x, -s.ndc_y, s.depth, s.convention);
      };
      break;
    case ConsumerMistake::ignores_oblique_row:
      c.view_position = [](const oracle::DepthSample<T>& s) {
        const Matrix4<T>& p = s.projection;
        const T z_ndc = s.convention == Convention::gl ? T(2) * s.depth - T(1) : s.depth;
        const T z = p(2, 3) / (z_ndc * p(3, 2) - p(2, 2));
        const T w = p(3, 2) * z;
        return Vector3<T>((s.ndc_x * w - p(0, 2) * z) / p(0, 0),
                          (s.ndc_y * w - p(1, 2) * z) / p(1, 1), z);
      };
      break;
    case ConsumerMistake::transposed_matrix:
      c.view_position = [](const oracle::DepthSample<T>& s) {
        const T z = s.convention == Convention::gl ? T(2) * s.depth - T(1) : s.depth;
        const Vector4<T> v =
            s.projection.inverse().transpose() * Vector4<T>(s.ndc_x, s.ndc_y, z, T(1));
        return Vector3<T>(v.template head<3>() / v.w());
      };
      break;
    case ConsumerMistake::linearises_with_near_far:
      c.linear_depth = [](const oracle::DepthSample<T>& s) {
        // 1 / n and 1 / f off the perspective M in its convention (n, f distances along its view
        // axis, which M43 = -1 or +1 points down -z or +z), and the depth turned forward on
        // reversed Z, as _ZBufferParams do: n f / (f - d (f - n)) as
        // 1 / ((1 / f - 1 / n) d + 1 / n), finite for an infinite f. The face at NDC z = F is at
        // the distance b / (F - a M43) (M33 = a, M34 = b).
        const T a = s.original(2, 2), b = s.original(2, 3), axis = s.original(3, 2);
        const bool reversed = s.convention == Convention::reversed_z;
        const T near_face = s.convention == Convention::gl ? T(-1) : reversed ? T(1) : T(0);
        const T far_face = reversed ? T(0) : T(1);
        const T near_inverse = (near_face - a * axis) / b, far_inverse = (far_face - a * axis) / b;
        const T d = reversed ? T(1) - s.depth : s.depth;  // [0, 1], forward
        return T(1) / ((far_inverse - near_inverse) * d + near_inverse);
      };
      break;
    case ConsumerMistake::world_with_original:
      c.world_position = [](const oracle::DepthSample<T>& s) {
        return world_position(s.original, s.view, s.ndc_x, s.ndc_y, s.depth, s.convention);
      };
      break;
    case ConsumerMistake::world_through_view:
      c.world_position = [](const oracle::DepthSample<T>& s) {
        const Vector3<T> v = view_position(s.projection, s.ndc_x, s.ndc_y, s.depth, s.convention);
        return Vector3<T>((s.view * Vector4<T>(v.x(), v.y(), v.z(), T(1))).template head<3>());
      };
      break;
    case ConsumerMistake::gl_planes_on_any_matrix:
      c.culling_planes = [](const Matrix4<T>& m, Convention) {
        return frustum_planes(m, Convention::gl);
      };
      break;
    case ConsumerMistake::planes_of_transpose:
      c.culling_planes = [](const Matrix4<T>& m, Convention k) {
        return frustum_planes(Matrix4<T>(m.transpose()), k);
      };
      break;
    case ConsumerMistake::plane_without_translation:
      c.camera_plane = [](const Matrix4<T>& view, const Vector4<T>& plane) {
        const Vector3<T> n = view.template topLeftCorner<3, 3>() * plane.template head<3>();
        return Vector4<T>(n.x(), n.y(), n.z(), plane.w());
      };
      break;
    case ConsumerMistake::plane_flipped_for_mirrors:
      c.camera_plane = [](const Matrix4<T>& view, const Vector4<T>& plane) {
        const Vector4<T> p = plane_in_camera(view, plane);
        return view.template topLeftCorner<3, 3>().determinant() < 0 ? Vector4<T>(-p) : p;
      };
      break;
    case ConsumerMistake::plane_through_view:
      c.camera_plane = [](const Matrix4<T>& view, const Vector4<T>& plane) {
        return Vector4<T>(view * plane);
      };
      break;
    case ConsumerMistake::mirror_by_reflected_look_at:
      c.mirror_view = [](const Matrix4<T>& view, const Vector4<T>& plane) {
        const Matrix4<T> to_world = view.inverse();
        const T length = plane.template head<3>().norm();
        const Vector3<T> n = plane.template head<3>() / length;
        const T d = plane.w() / length;
        auto point = [&](const Vector3<T>& p) -> Vector3<T> {
          return p - T(2) * (n.dot(p) + d) * n;
        };
        auto direction = [&](const Vector3<T>& v) -> Vector3<T> { return v - T(2) * n.dot(v) * n; };
        const Vector3<T> eye = point(to_world.template topRightCorner<3, 1>());
        const Vector3<T> forward = direction(-to_world.template block<3, 1>(0, 2)).normalized();
        const Vector3<T> side =
            forward.cross(direction(to_world.template block<3, 1>(0, 1))).normalized();
        const Vector3<T> up = side.cross(forward);
        Matrix4<T> out = Matrix4<T>::Identity();
        out.template block<1, 3>(0, 0) = side.transpose();
        out.template block<1, 3>(1, 0) = up.transpose();
        out.template block<1, 3>(2, 0) = -forward.transpose();
        out(0, 3) = -side.dot(eye);
        out(1, 3) = -up.dot(eye);
        out(2, 3) = forward.dot(eye);
        return out;
      };
      break;
    case ConsumerMistake::portal_without_turn:
      c.portal_view = [](const Matrix4<T>& view, const Matrix4<T>& frame,
                         const Matrix4<T>& linked) {
        return Matrix4<T>(view * frame * linked.inverse());
      };
      break;
    case ConsumerMistake::corners_of_oblique_matrix:
      c.corners = [](const Matrix4<T>& m, const Matrix4<T>&, Convention k) {
        std::vector<Vector3<T>> out;
        for (const Vector4<T>& v : view_volume_corners(m, k))
          out.push_back(v.template head<3>() / v.w());
        return out;
      };
      break;
  }
  return c;
}

template <class T>
void explain_consumer(const oracle::ConsumerAsk<T>& ask, const std::vector<T>& answer_as_given,
                      oracle::ConsumerFinding& finding) {
  if (!finding.judged || finding.holds) return;
  finding.answers_show = answers_show(ask, answer_as_given);
  // World positions are compared in the pass camera's space, where the pixel's ray is: in world
  // space a camera far from the origin makes every answer alike to its translation's digits.
  std::function<std::vector<T>(const std::vector<T>&)> comparable = [](const std::vector<T>& v) {
    return v;
  };
  if (ask.kind == ConsumerKind::world_position) {
    if (const auto s = sample_of(ask)) {
      comparable = [view = s->view](const std::vector<T>& v) { return in_pass_camera(view, v); };
    }
  }
  const std::vector<T> answer = comparable(answer_as_given);
  // An answer as close to the correct one is a precision finding, no formula's.
  try {
    if (alike_answers(ask.kind, answer, comparable(ask.call(oracle::reference_consumers<T>())))) {
      finding.answers_show +=
          (finding.answers_show.empty() ? "" : "; ") +
          std::string(
              "it agrees with the right answer to half of the precision's digits, too "
              "close for the catalogue's formulas to be told from it");
      return;
    }
  } catch (...) {
  }
  std::string names;
  for (ConsumerMistake m : all_consumer_mistakes) {
    const ConsumerMistakeEntry& e = consumer_mistake_entry(m);
    if (e.kind != ask.kind) continue;
    try {
      if (alike_answers(ask.kind, answer, comparable(ask.call(mistaken_consumers<T>(m)))))
        names += (names.empty() ? "" : " or ") + std::string(e.name);
    } catch (...) {
      // a wrong function that cannot answer these inputs is no cause of this answer
    }
  }
  finding.likely_cause = names;
}

namespace {

/// `likely_cause` without kNamedBeforeShrinking, and whether it had it.
std::pair<std::string, bool> undecorated(const std::string& likely_cause) {
  const std::string mark = kNamedBeforeShrinking;
  if (likely_cause.size() > mark.size() &&
      likely_cause.compare(likely_cause.size() - mark.size(), mark.size(), mark) == 0)
    return {likely_cause.substr(0, likely_cause.size() - mark.size()), true};
  return {likely_cause, false};
}

}  // namespace

std::string consumer_cause_line(const std::string& likely_cause) {
  if (likely_cause.empty()) return "";
  const auto [names, before_shrinking] = undecorated(likely_cause);
  const std::string where =
      before_shrinking ? ", named on the first failing case: on this shrunk one the answer is "
                         "within half of the digits of the correct one"
                       : "";
  if (const auto m = parse_consumer_mistake(names)) {
    const ConsumerMistakeEntry& e = consumer_mistake_entry(*m);
    return "likely cause: " + names + ": " + std::string(e.effect) + " (" + std::string(e.title) +
           where + "); fix: " + std::string(e.fix);
  }
  return "likely cause: " + names + (before_shrinking ? " (" + where.substr(2) + ")" : "");
}

std::string consumer_cause_markdown(const std::string& decorated, const std::string& shows) {
  if (decorated.empty() && shows.empty()) return "";
  const auto [likely_cause, before_shrinking] = undecorated(decorated);
  std::ostringstream md;
  md << "## Likely cause\n\n";
  if (!shows.empty()) md << "What the answers show: " << shows << ".\n\n";
  if (likely_cause.empty()) {
    md << "No known mistake gives this answer (catalogue: docs/consumers.md): what it shows, "
          "above, is what is known of it.\n\n";
    return md.str();
  }
  std::vector<std::string> names;
  for (std::size_t at = 0; at <= likely_cause.size();) {
    const std::size_t end = std::min(likely_cause.find(" or ", at), likely_cause.size());
    names.push_back(likely_cause.substr(at, end - at));
    at = end + 4;
  }
  if (names.size() > 1)
    md << "Each of these gives the answer; the inputs asked do not tell them apart.\n\n";
  for (const std::string& name : names) {
    const auto m = parse_consumer_mistake(name);
    if (!m) continue;
    const ConsumerMistakeEntry& e = consumer_mistake_entry(*m);
    std::string effect(e.effect);
    if (!effect.empty()) effect[0] = static_cast<char>(std::toupper(effect[0]));
    md << "**`" << e.name << "`: " << effect << ".** The code that gives it (" << e.title
       << "): " << e.explanation << "\n\nFix: " << e.fix << "\n\n";
  }
  if (before_shrinking)
    md << "Named on the run's first failing case, where the answer was this wrong function's on "
          "the same inputs (to half of the precision's digits) and not the correct one's; on "
          "this shrunk case the answer is that close to the correct one too, so the case alone "
          "names nothing (catalogue: docs/consumers.md).\n\n";
  else
    md << "The answer is this wrong function's on the same inputs (to half of the precision's "
          "digits), and not the correct one's (catalogue: docs/consumers.md).\n\n";
  return md.str();
}

#define OBLIQUE_CONSUMER_MISTAKES(T)                                                      \
  template Consumers<T> mistaken_consumers<T>(ConsumerMistake);                           \
  template void explain_consumer<T>(const oracle::ConsumerAsk<T>&, const std::vector<T>&, \
                                    oracle::ConsumerFinding&);
OBLIQUE_CONSUMER_MISTAKES(float)
OBLIQUE_CONSUMER_MISTAKES(double)
OBLIQUE_CONSUMER_MISTAKES(long double)
#undef OBLIQUE_CONSUMER_MISTAKES

}  // namespace oblique::mistakes
