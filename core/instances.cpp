// apply() for float, double and long double, compiled once (oblique::core_instances): files that
// link it see OBLIQUE_EXTERN_TEMPLATES and do not instantiate apply() themselves.
#include "oblique/oblique.h"

namespace oblique {

template ObliqueResult<float> apply<float>(const Matrix4<float>&, const Vector4<float>&, Convention,
                                           Method);
template ObliqueResult<double> apply<double>(const Matrix4<double>&, const Vector4<double>&,
                                             Convention, Method);
template ObliqueResult<long double> apply<long double>(const Matrix4<long double>&,
                                                       const Vector4<long double>&, Convention,
                                                       Method);

}  // namespace oblique
