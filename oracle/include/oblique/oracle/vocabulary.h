// The case vocabulary's checks and properties (oblique/cases/checks.h, property.h) named in the
// judge's namespace, so that oracle::Checks and cases::Checks are one type said either way.
#pragma once

#include "oblique/cases/checks.h"
#include "oblique/cases/property.h"

namespace oblique::oracle {

using cases::all_properties;
using cases::Checks;
using cases::Property;
using cases::property_name;
using cases::StatusContract;

}  // namespace oblique::oracle
