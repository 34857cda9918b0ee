// Your oblique-clipping function, as the property suite and the fuzz driver see it. adapt() wraps
// a function of any of these shapes (T is float, double or long double):
//
//   void   f(T m[16], const T plane[4]);                  // in place, answers only
//   bool   f(T m[16], const T plane[4]);                  // in place, false = refused
//   Status f(T m[16], const T plane[4]);                  // in place, with oblique's statuses
//   void|bool|Status f(const T m[16], const T plane[4], T out[16]);   // out of place
//   ObliqueResult<T> or Answer<T> f(const Matrix4<T>&, const Vector4<T>&, Convention);
//
// with the 16 numbers in `Layout::row_major` (m[4 * row + column]) or `Layout::column_major`
// (m[4 * column + row], OpenGL's and Listing 5.1's) order, or `Layout::row_vectors` for an engine
// whose points are rows (v M: DirectXMath, D3DX, XNA, Unity's C# API is not one): its matrix is
// the transpose of the column-vector one, stored row by row, and its oblique row is M's third
// column (Lengyel's Direct3D version). The plane is (a, b, c, d) in camera space, the side seen
// and kept where a x + b y + c z + d > 0, whichever way vectors are written.
//
// A function that takes no convention serves one, and says which:
//   adapt<float>("make_oblique", Layout::column_major, Convention::gl, make_oblique)
// and a test's default contract (oblique/cases/contract.h) checks it in that convention
// only. A function that takes the convention serves all three:
//   adapt<double>("mine", Layout::row_major, mine)
#pragma once

#include <functional>
#include <string>
#include <type_traits>
#include <utility>

#include "oblique/oracle/implementation.h"
#include "oblique/projection.h"
#include "oblique/result.h"

namespace oblique {

/// How a function stores a 4x4 matrix in 16 numbers, and which way it multiplies vectors.
enum class Layout {
  row_major,     ///< column vectors (M v), m[4 * row + column]
  column_major,  ///< column vectors (M v), m[4 * column + row]: OpenGL's, GLM's, Listing 5.1's
  /// Row vectors (v R, R = M^T: DirectXMath, D3DX), R stored row by row, m[4 * row + column] of
  /// R: the same 16 numbers as column_major. A function of Matrix4<T> is handed R = M^T and its
  /// answer R' read back as M' = R'^T.
  row_vectors,
};

namespace adapting {

template <class T>
void store(const Matrix4<T>& m, Layout layout, T* out) {
  // row_vectors stores R = M^T by rows: M's entry (r, c) at 4 c + r, as column_major does.
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) out[layout == Layout::row_major ? 4 * r + c : 4 * c + r] = m(r, c);
  }
}

template <class T>
Matrix4<T> load(const T* in, Layout layout) {
  Matrix4<T> m;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) m(r, c) = in[layout == Layout::row_major ? 4 * r + c : 4 * c + r];
  }
  return m;
}

/// The matrix a function of Matrix4<T> is handed for M in `layout` (and M' from its answer: the
/// same map, a transpose being its own inverse).
template <class T>
Matrix4<T> as_handed(const Matrix4<T>& m, Layout layout) {
  return layout == Layout::row_vectors ? Matrix4<T>(m.transpose()) : m;
}

/// A refusal of a function that says only "no" (returns false): judged as any refusal.
template <class R>
Status status_of(const R& returned) {
  if constexpr (std::is_same_v<R, Status>) {
    return returned;
  } else {
    return returned ? Status::ok : Status::invalid_input;
  }
}

template <class R>
constexpr bool kReportsStatuses = std::is_same_v<R, bool> || std::is_same_v<R, Status>;
template <class R>
constexpr bool kOwnRefusals = std::is_same_v<R, bool>;

}  // namespace adapting

namespace adapting {

template <class T, class F>
oracle::Implementation<T> wrap(std::string name, Layout layout, F function,
                               std::function<bool(Convention, const Matrix4<T>&)> accepts) {
  oracle::Implementation<T> impl;
  impl.name = std::move(name);
  impl.accepts = accepts ? std::move(accepts) : [](Convention, const Matrix4<T>&) { return true; };
  if constexpr (std::is_invocable_v<F&, const Matrix4<T>&, const Vector4<T>&, Convention>) {
    using R = std::invoke_result_t<F&, const Matrix4<T>&, const Vector4<T>&, Convention>;
    static_assert(std::is_same_v<R, ObliqueResult<T>> || std::is_same_v<R, Answer<T>>,
                  "a matrix-shaped function returns ObliqueResult<T> or Answer<T>");
    impl.reports_statuses = true;
    impl.run = [function, layout](const Matrix4<T>& m, const Vector4<T>& c,
                                  Convention convention) mutable {
      const R r = function(adapting::as_handed(m, layout), c, convention);
      return Answer<T>{r.status, adapting::as_handed(r.projection, layout)};
    };
  } else if constexpr (std::is_invocable_v<F&, T*, const T*>) {
    using R = std::invoke_result_t<F&, T*, const T*>;
    impl.reports_statuses = adapting::kReportsStatuses<R>;
    impl.own_refusals = adapting::kOwnRefusals<R>;
    impl.run = [function, layout](const Matrix4<T>& m, const Vector4<T>& c, Convention) mutable {
      T numbers[16];
      const T plane[4] = {c(0), c(1), c(2), c(3)};
      adapting::store(m, layout, numbers);
      Status status = Status::ok;
      if constexpr (std::is_void_v<R>) {
        function(numbers, plane);
      } else {
        status = adapting::status_of<R>(function(numbers, plane));
      }
      return Answer<T>{status, adapting::load(numbers, layout)};
    };
  } else {
    static_assert(std::is_invocable_v<F&, const T*, const T*, T*>,
                  "adapt(): the function has none of the shapes in oblique/oracle/adapter.h");
    using R = std::invoke_result_t<F&, const T*, const T*, T*>;
    impl.reports_statuses = adapting::kReportsStatuses<R>;
    impl.own_refusals = adapting::kOwnRefusals<R>;
    impl.run = [function, layout](const Matrix4<T>& m, const Vector4<T>& c, Convention) mutable {
      T numbers[16], out[16] = {};
      const T plane[4] = {c(0), c(1), c(2), c(3)};
      adapting::store(m, layout, numbers);
      Status status = Status::ok;
      if constexpr (std::is_void_v<R>) {
        function(numbers, plane, out);
      } else {
        status = adapting::status_of<R>(function(numbers, plane, out));
      }
      return Answer<T>{status, adapting::load(out, layout)};
    };
  }
  return impl;
}

}  // namespace adapting

/// Wraps `function` (see the shapes above), which serves `convention` only, as an implementation
/// named `name` for oblique::testing and oblique::fuzzing. `accepts` limits the inputs it is
/// given (e.g. perspective_shape_only for a closed form); by default it is given every input of
/// its convention.
template <class T, class F>
oracle::Implementation<T> adapt(
    std::string name, Layout layout, Convention convention, F function,
    std::function<bool(Convention, const Matrix4<T>&)> accepts = nullptr) {
  oracle::Implementation<T> impl =
      adapting::wrap<T>(std::move(name), layout, std::move(function), std::move(accepts));
  impl.conventions = {convention};
  return impl;
}

/// Wraps a function that takes the convention (ObliqueResult<T> or Answer<T> f(const
/// Matrix4<T>&, const Vector4<T>&, Convention)): it serves every convention.
template <class T, class F>
oracle::Implementation<T> adapt(
    std::string name, Layout layout, F function,
    std::function<bool(Convention, const Matrix4<T>&)> accepts = nullptr) {
  static_assert(std::is_invocable_v<F&, const Matrix4<T>&, const Vector4<T>&, Convention>,
                "adapt(): a function that takes no convention serves one; say which: "
                "adapt<T>(name, layout, Convention::gl, function)");
  return adapting::wrap<T>(std::move(name), layout, std::move(function), std::move(accepts));
}

// Presets for `adapt`'s `accepts`, the inputs a closed form is meant for. What each admits, by
// generator family (oblique/cases/case_kinds.h):
//
//   preset                   perspective off_axis jittered infinite y/x/xy_flipped left_handed
//   perspective_shape_only        yes       yes      yes      yes        yes           yes
//   engine_perspective_only       yes       yes      yes      yes        yes           no
//
// and neither admits orthographic, rotated, general or stereo_shift matrices.
// perspective_shape_only admits a left-handed M43 = +1 and any sign of M34, which a closed form
// written for the matrix a right-handed engine builds (Lengyel's Listing 5.1 assumes M43 = -1)
// need not handle. Give such a function engine_perspective_only and the engine contract
// (contract.h's engine_contract()), which claims exactly its families: a closed form that takes
// a sign from camera space (right only while M11 > 0 and M22 > 0) then fails on the flipped
// matrices engines build, as it should.

/// Only matrices of the standard perspective shape (projection.h's has_perspective_shape(): the
/// entries a closed form reads, whatever their signs).
template <class T>
bool perspective_shape_only(Convention, const Matrix4<T>& m) {
  return has_perspective_shape(m);
}

/// Only the perspective matrices engines build (glFrustum, glm::perspective, a right-handed
/// Direct3D or Vulkan projection, each also flipped: Vulkan's y flip makes M22 < 0, a mirror
/// pass's x flip M11 < 0): the perspective shape with M43 = -1 and the near plane in front of
/// the camera (M34 < 0; reversed Z, where depth runs the other way: M34 > 0). Jittered and
/// off-axis (M13, M23 of either sign) and infinite ones included.
template <class T>
bool engine_perspective_only(Convention convention, const Matrix4<T>& m) {
  const bool near_in_front = convention == Convention::reversed_z ? m(2, 3) > T(0) : m(2, 3) < T(0);
  return has_perspective_shape(m) && m(3, 2) == T(-1) && near_in_front;
}

}  // namespace oblique
