// oblique::core: apply() and apply_batch() compiled once, for float, double and long double.
#include "oblique/definitions.h"

namespace oblique {

#define OBLIQUE_INSTANTIATE(T)                                                                  \
  template ObliqueResult<T> apply<T>(const Matrix4<T>&, const Vector4<T>&, Convention, Method); \
  template void apply_batch<T>(const Matrix4<T>*, const Vector4<T>*, std::size_t, Convention,   \
                               Method, Matrix4<T>*, Status*);                                   \
  template void apply_batch<T>(const Matrix4<T>*, const Vector4<T>*, std::size_t, Convention,   \
                               Method, ObliqueResult<T>*);

OBLIQUE_INSTANTIATE(float)
OBLIQUE_INSTANTIATE(double)
OBLIQUE_INSTANTIATE(long double)

#undef OBLIQUE_INSTANTIATE

}  // namespace oblique
