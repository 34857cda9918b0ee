// The engine's make_oblique end to end: its answers drawn on a real rasterizer (llvmpipe,
// headless) and judged pixel by pixel (oblique/testing/raster.h; link oblique::testing_raster).
// Skipped, saying what to install, on a machine without EGL.
#include <oblique/testing/raster.h>

#include "engine_adapter.h"

OBLIQUE_RASTER_TEST(Engine, makeObliqueIsRightOnTheRasterizer, engine_checks::make_oblique,
                    engine_checks::contract)
