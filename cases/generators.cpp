// oblique::generators: the RapidCheck generators of cases compiled once per scalar type (CMake's
// oblique_add_instances).
#include "oblique/cases/generators.h"

#ifndef OBLIQUE_SCALAR
#error "compiled once per scalar type, with OBLIQUE_SCALAR defined (oblique_add_instances)"
#endif

namespace oblique::cases {

OBLIQUE_GENERATOR_INSTANCES(template, OBLIQUE_SCALAR)

}  // namespace oblique::cases
