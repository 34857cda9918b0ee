// oblique::core: apply() compiled once per scalar type (float, double, long double; CMake's
// oblique_add_instances), with detail::apply_checked(), which the core's white-box tests call.
// The accurate method it hands stiff requests to is oblique::accurate's (core/src/accurate.cpp).
#include "oblique/definitions.h"

#ifndef OBLIQUE_SCALAR
#error "compiled once per scalar type, with OBLIQUE_SCALAR defined (oblique_add_instances)"
#endif

namespace oblique {

OBLIQUE_ACCURATE_INSTANCES(extern template, OBLIQUE_SCALAR)
OBLIQUE_APPLY_INSTANCES(template, OBLIQUE_SCALAR)

}  // namespace oblique
