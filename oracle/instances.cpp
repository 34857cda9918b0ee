// oblique::properties: the checker's constructors and judgements (judge() on a Problem and on a
// FilteredProblem) compiled once per scalar type (CMake's oblique_add_instances).
#include "oblique/oracle/filtered.h"

#ifndef OBLIQUE_SCALAR
#error "compiled once per scalar type, with OBLIQUE_SCALAR defined (oblique_add_instances)"
#endif

namespace oblique::oracle {

OBLIQUE_CHECKER_INSTANCES(template, OBLIQUE_SCALAR)

}  // namespace oblique::oracle
