// The engine's make_oblique profiled: how many bits its answers lose, where, and how fast it is,
// beside the core's methods on the same cases (oblique::testing's profile_accuracy()). The report
// goes to $OBLIQUE_REPORT_DIR/Engine.makeObliqueAccuracy.accuracy/accuracy.md.
#include "engine_adapter.h"

OBLIQUE_ACCURACY_REPORT(Engine, makeObliqueAccuracy, engine_checks::make_oblique,
                        engine_checks::contract)
