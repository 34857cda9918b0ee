// GoogleTest printers for the core's enums, so failures show names instead of bytes.
#pragma once

#include <ostream>

#include "oblique/depth_convention.h"
#include "oblique/oblique.h"
#include "oblique/status.h"

namespace oblique {

inline void PrintTo(Status s, std::ostream* os) {
  *os << status_code(s);
}
inline void PrintTo(Convention c, std::ostream* os) {
  *os << convention_name(c);
}
inline void PrintTo(Method m, std::ostream* os) {
  *os << method_name(m);
}

}  // namespace oblique
