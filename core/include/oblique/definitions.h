// The definitions of apply() and apply_batch(): what oblique::core compiles once, for float,
// double and long double (core/src/oblique.cpp, batch.cpp and accurate.cpp). Include this header
// only for a header-only build (any other scalar type, or the core compiled with your own flags);
// otherwise include oblique/oblique.h (and oblique/batch.h) and link oblique::core.
//
// apply() answers the common request (ordinary_input(): the perspective shape, every entry zero
// or normal, a moderate spread) with the closed form at once; every other request goes through
// apply_checked(), which runs the documented checks one by one and then the method.
#pragma once

#include <cstddef>
#include <cstring>

#include "oblique/batch.h"
#include "oblique/detail/accurate/accurate.h"
#include "oblique/detail/batch_lanes.h"
#include "oblique/detail/closed_form.h"
#include "oblique/detail/closed_form_steps.h"
#include "oblique/detail/general_method.h"
#include "oblique/detail/input_checks.h"
#include "oblique/detail/plane_scaling.h"
#include "oblique/numeric/magnitudes.h"
#include "oblique/oblique.h"
#include "oblique/projection.h"

namespace oblique {
namespace detail {

/// plane_scale(plane), read from the exponent fields ordinary_input() found where it could.
template <class T>
OBLIQUE_ALWAYS_INLINE PlaneScale ordinary_plane_scale(const Vector4<T>& plane,
                                                      const OrdinaryInput& input) {
  if constexpr (ExponentBits<T>::known) {
    if (input.ordinary) return plane_scale_of_fields<T>(input.plane_high, input.plane_low);
  }
  return plane_scale(plane);
}

/// The closed form's answer as apply() gives it: the hand-offs to the accurate method taken.
template <class T>
OBLIQUE_ALWAYS_INLINE ObliqueResult<T> closed_form_result(const Matrix4<T>& m,
                                                          const Vector4<T>& plane,
                                                          Convention convention,
                                                          const PlaneScale& scale,
                                                          Entries entries) {
  Answer<T> answer;
  if (closed_form(m, plane, convention, scale, entries, answer) != Step::handed_on)
    return answer.result(m, Method::closed_form);
  return handed_to_accurate(m, plane, convention);
}

/// apply()'s checks one by one, in the documented order, and the method; `ordinary`: the
/// request passed ordinary_input() (so the first four checks pass).
template <class T>
OBLIQUE_NOINLINE ObliqueResult<T> apply_checked(const Matrix4<T>& projection,
                                                const Vector4<T>& plane, Convention convention,
                                                Method method, Entries entries) {
  if (entries == Entries::unchecked) {
    if (!all_finite(projection)) {
      return refuse(projection, method, Status::invalid_input,
                    "the projection matrix has a NaN or infinite entry");
    }
    if (!all_finite(plane)) {
      return refuse(projection, method, Status::invalid_input,
                    "the clip plane has a NaN or infinite component");
    }
    if (magnitude_spread_exceeds<max_magnitude_spread<T>()>(projection)) {
      return refuse(projection, method, Status::out_of_range,
                    "the projection's nonzero entries span more binades than twice the "
                    "precision of the scalar type (max_magnitude_spread)");
    }
  }
  const Shape shape = Shape(entries == Entries::ordinary || has_perspective_shape(projection));
  if (method == Method::automatic) {
    method = shape == Shape::perspective ? Method::closed_form : Method::general;
  }
  if (method == Method::closed_form) {
    if (shape != Shape::perspective) {
      return refuse(projection, method, Status::invalid_input,
                    "closed_form needs the standard perspective shape (zeros outside "
                    "M11, M13, M22, M23, M33, M34, M43; M43 != 0); use auto or general");
    }
    return closed_form_result(projection, plane, convention, plane_scale(plane),
                              Entries::unchecked);
  }
  if (method == Method::accurate) {
    return accurate(projection, plane, convention, shape, plane_scale(plane), Entries::unchecked);
  }
  Answer<T> answer;
  if (general(projection, plane, convention, answer) != Step::handed_on)
    return answer.result(projection, Method::general);
  return handed_to_accurate(projection, plane, convention);
}

/// apply_batch()'s answer to request i, one request at a time.
template <class T>
OBLIQUE_ALWAYS_INLINE void batch_answer(const Matrix4<T>& m, const Vector4<T>& plane,
                                        Convention convention, Method method, Matrix4<T>& out,
                                        Status& status) {
  const OrdinaryInput input = ordinary_input(m, plane);
  Answer<T> answer;
  if (input.ordinary && (method == Method::automatic || method == Method::closed_form) &&
      closed_form(m, plane, convention, ordinary_plane_scale(plane, input), Entries::ordinary,
                  answer) != Step::handed_on) {
    if (&out != &m) out = m;
    if (answer.status == Status::ok) {
      for (int j = 0; j < 4; ++j) out(2, j) = answer.row3(j);
    }
    status = answer.status;
  } else {
    const ObliqueResult<T> r = apply_checked(m, plane, convention, method, input.entries());
    out = r.projection;
    status = r.status;
  }
}

/// batch_answer() kept out of its caller: the requests a block of closed_form_lanes() leaves.
template <class T>
OBLIQUE_NOINLINE void batch_answer_apart(const Matrix4<T>& m, const Vector4<T>& plane,
                                         Convention convention, Method method, Matrix4<T>& out,
                                         Status& status) {
  batch_answer(m, plane, convention, method, out, status);
}

/// apply_batch()'s blocks: W closed-form requests at a time through closed_form_lanes()
/// (detail/batch_lanes.h), each block read before it is answered; `answered(j, lanes, k)` for
/// request j answered by lane k, `apart(j)` for a request the block leaves. Returns how many
/// requests the blocks covered (a multiple of W, 0 without a block path or for another method); the
/// rest go one by one.
template <class T, bool FarCorner, class Answered, class Apart>
OBLIQUE_ALWAYS_INLINE std::size_t closed_form_blocks(const Matrix4<T>* projections,
                                                     const Vector4<T>* planes, std::size_t count,
                                                     Convention convention, Method method,
                                                     Answered&& answered, Apart&& apart) {
  std::size_t i = 0;
  if constexpr (closed_form_lanes_available<T>()) {
    if (method == Method::automatic || method == Method::closed_form) {
      constexpr int W = closed_form_lane_count<T>;
      const ConventionTable<T>& table = convention_table<T>(convention);
      ClosedFormLanes<T, W> lanes;
      const bool avx2 = closed_form_block_avx2_supported();
      for (; count - i >= std::size_t(W); i += W) {
        closed_form_block_on<T, W, FarCorner>(avx2, projections + i, planes + i, table, lanes);
        for (int k = 0; k < W; ++k) {
          const std::size_t j = i + std::size_t(k);
          if (lanes.fast[k] != T(0)) {
            answered(j, lanes, k);
          } else {
            apart(j);
          }
        }
      }
    }
  }
  return i;
}

/// The accurate method for an ordinary request, out of apply()'s line: its frame is large, and
/// apply()'s closed-form path should not pay for it.
template <class T>
OBLIQUE_NOINLINE ObliqueResult<T> accurate_ordinary(const Matrix4<T>& m, const Vector4<T>& plane,
                                                    Convention convention, PlaneScale scale) {
  return accurate(m, plane, convention, Shape::perspective, scale, Entries::ordinary);
}

}  // namespace detail

template <class T>
ObliqueResult<T> apply(const Matrix4<T>& projection, const Vector4<T>& plane, Convention convention,
                       Method method) {
  const detail::OrdinaryInput input = detail::ordinary_input(projection, plane);
  if (input.ordinary && (method == Method::automatic || method == Method::closed_form)) {
    return detail::closed_form_result(projection, plane, convention,
                                      detail::ordinary_plane_scale(plane, input),
                                      detail::Entries::ordinary);
  }
  if (input.ordinary && method == Method::accurate) {
    return detail::accurate_ordinary(projection, plane, convention,
                                     detail::ordinary_plane_scale(plane, input));
  }
  return detail::apply_checked(projection, plane, convention, method, input.entries());
}

/// apply() over `count` requests in one convention: for each i, out[i] and statuses[i] are the
/// projection and status of apply(projections[i], planes[i], convention, method) (M' when ok,
/// the input matrix otherwise), bit for bit. The closed form's ordinary requests are answered
/// without building an ObliqueResult. `out` may be `projections` (in place); the arrays must
/// otherwise not overlap.
template <class T>
void apply_batch(const Matrix4<T>* projections, const Vector4<T>* planes, std::size_t count,
                 Convention convention, Method method, Matrix4<T>* out, Status* statuses) {
  std::size_t i = detail::closed_form_blocks<T, false>(
      projections, planes, count, convention, method,
      [&](std::size_t j, const auto& lanes, int k) {
        if (&out[j] != &projections[j])
          std::memcpy(out[j].data(), projections[j].data(), sizeof(T) * 16);
        for (int e = 0; e < 4; ++e) out[j](2, e) = lanes.row3[e][k];
        statuses[j] = Status::ok;
      },
      [&](std::size_t j) {
        detail::batch_answer_apart(projections[j], planes[j], convention, method, out[j],
                                   statuses[j]);
      });
  for (; i < count; ++i)
    detail::batch_answer(projections[i], planes[i], convention, method, out[i], statuses[i]);
}

/// apply() over `count` requests in one convention: results[i] = apply(projections[i], planes[i],
/// convention, method).
template <class T>
void apply_batch(const Matrix4<T>* projections, const Vector4<T>* planes, std::size_t count,
                 Convention convention, Method method, ObliqueResult<T>* results) {
  std::size_t i = detail::closed_form_blocks<T, true>(
      projections, planes, count, convention, method,
      [&](std::size_t j, const auto& lanes, int k) {
        ObliqueResult<T>& r = results[j];
        r.status = Status::ok;
        r.detail = {};
        std::memcpy(r.projection.data(), projections[j].data(), sizeof(T) * 16);
        for (int e = 0; e < 4; ++e) {
          r.projection(2, e) = lanes.row3[e][k];
          r.far_corner(e) = lanes.q[e][k];
        }
        r.method = Method::closed_form;
      },
      [&](std::size_t j) { results[j] = apply(projections[j], planes[j], convention, method); });
  for (; i < count; ++i) results[i] = apply(projections[i], planes[i], convention, method);
}

/// The instances the core's three libraries compile for T = float, double and long double, one
/// macro per library: oblique::core apply() (core/src/oblique.cpp), oblique::accurate the accurate
/// method (core/src/accurate.cpp), oblique::batch apply_batch() (core/src/batch.cpp). `declare` is
/// `template` there and `extern template` where a library uses another's instances, and where
/// OBLIQUE_LINKED_INSTANCES is defined: a program that links the libraries and includes this
/// header for its declarations (the core's white-box tests do) then compiles none of them again.
/// Without it, a file including this header compiles them with its own flags, and its copies
/// come first at link.
#define OBLIQUE_APPLY_INSTANCES(declare, T)                                                    \
  declare ObliqueResult<T> apply<T>(const Matrix4<T>&, const Vector4<T>&, Convention, Method); \
  declare ObliqueResult<T> detail::apply_checked<T>(const Matrix4<T>&, const Vector4<T>&,      \
                                                    Convention, Method, detail::Entries);
#define OBLIQUE_ACCURATE_INSTANCES(declare, T)                                                   \
  declare ObliqueResult<T> detail::accurate<T>(const Matrix4<T>&, const Vector4<T>&, Convention, \
                                               detail::Shape, const PlaneScale&, detail::Entries);
#define OBLIQUE_BATCH_INSTANCES(declare, T)                                                  \
  declare void apply_batch<T>(const Matrix4<T>*, const Vector4<T>*, std::size_t, Convention, \
                              Method, Matrix4<T>*, Status*);                                 \
  declare void apply_batch<T>(const Matrix4<T>*, const Vector4<T>*, std::size_t, Convention, \
                              Method, ObliqueResult<T>*);
#define OBLIQUE_CORE_INSTANCES(declare, T) \
  OBLIQUE_APPLY_INSTANCES(declare, T)      \
  OBLIQUE_ACCURATE_INSTANCES(declare, T)   \
  OBLIQUE_BATCH_INSTANCES(declare, T)

#if defined(OBLIQUE_LINKED_INSTANCES)
OBLIQUE_CORE_INSTANCES(extern template, float)
OBLIQUE_CORE_INSTANCES(extern template, double)
OBLIQUE_CORE_INSTANCES(extern template, long double)
#endif

}  // namespace oblique
