// oblique::core: apply() and apply_batch() compiled once per scalar type (float, double, long
// double; CMake's oblique_add_instances), with the two entry points the core's white-box tests
// call: detail::apply_checked(), detail::accurate().
#include "oblique/definitions.h"

#ifndef OBLIQUE_SCALAR
#error "compiled once per scalar type, with OBLIQUE_SCALAR defined (oblique_add_instances)"
#endif

namespace oblique {

OBLIQUE_CORE_INSTANCES(template, OBLIQUE_SCALAR)

}  // namespace oblique
