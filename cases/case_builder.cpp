// The one case builder (case_builder.h) compiled once for float, double and long double.
#include "oblique/cases/detail/case_builder_definitions.h"

namespace oblique::cases {
inline namespace OBLIQUE_EIGEN_LAYOUT {

OBLIQUE_CASE_BUILDER_INSTANCES(template, float)
OBLIQUE_CASE_BUILDER_INSTANCES(template, double)
OBLIQUE_CASE_BUILDER_INSTANCES(template, long double)

}  // namespace OBLIQUE_EIGEN_LAYOUT
}  // namespace oblique::cases
