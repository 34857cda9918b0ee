// The property suite on the engine's make_oblique: one adapter, one contract (engine_adapter.h),
// one test.
#include "engine_adapter.h"

OBLIQUE_PROPERTY_TEST(Engine, makeObliqueHasEveryProperty, engine_checks::make_oblique,
                      engine_checks::contract)
