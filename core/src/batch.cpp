// oblique::batch: apply_batch() (batch.h) compiled once per scalar type (float, double, long
// double; CMake's oblique_add_instances). A request its closed-form lanes leave goes to
// oblique::core's apply() and detail::apply_checked().
#include "oblique/definitions.h"

#ifndef OBLIQUE_SCALAR
#error "compiled once per scalar type, with OBLIQUE_SCALAR defined (oblique_add_instances)"
#endif

namespace oblique {

OBLIQUE_APPLY_INSTANCES(extern template, OBLIQUE_SCALAR)
OBLIQUE_ACCURATE_INSTANCES(extern template, OBLIQUE_SCALAR)
OBLIQUE_BATCH_INSTANCES(template, OBLIQUE_SCALAR)

}  // namespace oblique
