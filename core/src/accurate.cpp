// oblique::accurate: the accurate method (detail::accurate(), detail/accurate/) compiled once per
// scalar type (float, double, long double; CMake's oblique_add_instances). apply() reaches it
// for Method::accurate and for the requests the closed form and the general method hand on.
#include "oblique/definitions.h"

#ifndef OBLIQUE_SCALAR
#error "compiled once per scalar type, with OBLIQUE_SCALAR defined (oblique_add_instances)"
#endif

namespace oblique {

OBLIQUE_ACCURATE_INSTANCES(template, OBLIQUE_SCALAR)

}  // namespace oblique
