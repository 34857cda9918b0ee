// apply() over many requests at once, in one convention: declarations (oblique::core compiles
// them for float, double and long double; a header-only build includes oblique/definitions.h).
#pragma once

#include <cstddef>

#include "oblique/oblique.h"

namespace oblique {

/// apply() over `count` requests in one convention: for each i, out[i] and statuses[i] are the
/// projection and status of apply(projections[i], planes[i], convention, method) (M' when ok,
/// the input matrix otherwise), bit for bit. The closed form's ordinary requests are answered
/// without building an ObliqueResult, in blocks over SIMD lanes where the build has them
/// (detail/batch_lanes.h). `out` may be `projections` (in place); the arrays must otherwise not
/// overlap.
template <class T>
void apply_batch(const Matrix4<T>* projections, const Vector4<T>* planes, std::size_t count,
                 Convention convention, Method method, Matrix4<T>* out, Status* statuses);

/// apply() over `count` requests in one convention: results[i] = apply(projections[i], planes[i],
/// convention, method).
template <class T>
void apply_batch(const Matrix4<T>* projections, const Vector4<T>* planes, std::size_t count,
                 Convention convention, Method method, ObliqueResult<T>* results);

}  // namespace oblique
