// The property suite's end-to-end check: your function's answers drawn on a real rasterizer
// (oblique::raster: OpenGL 4.5 through EGL, headless; llvmpipe unless told otherwise) and judged
// there, sample by sample: nothing behind C drawn, nothing of the original view volume on C's
// kept side clipped, no sample in a wrong pixel (docs/raster.md).
//
//   #include <oblique/testing/raster.h>   // link oblique::testing_raster
//
//   const auto mine = oblique::adapt<float>("make_oblique", oblique::Layout::column_major,
//                                            oblique::Convention::gl, make_oblique);
//   OBLIQUE_RASTER_TEST(MakeOblique, isRightOnTheRasterizer, mine, oblique::Contract{})
//
// One RapidCheck run (named "rasterizer") over the contract's families, conventions and places,
// shrunk on failure, with a report (Markdown, the flagged pixels' picture, the replay command) in
// OBLIQUE_REPORT_DIR as for the other properties. A machine without EGL skips the test, saying
// what to install. When the renderer trips one of its self-checks, the test fails as
// "inconclusive": that is no verdict about the function, and the message says so.
#pragma once

#include <vector>

#include "oblique/raster/raster.h"
#include "oblique/testing.h"

namespace oblique::testing {

struct RasterSettings {
  raster::Device device = raster::Device::software;
  int size = 128;  ///< each case's frame: size x size pixels, one sample each
  /// The depth buffers a case may be drawn into (each case picks one).
  std::vector<DepthBuffer> buffers{DepthBuffer::fixed24, DepthBuffer::float32};
};

/// Draws `impl`'s answers to cases of `contract` on the rasterizer and judges them; fails the
/// current GoogleTest test on a case that fails there (or is inconclusive), with a report, and
/// when the cases missed a family, convention or place of the contract. Compiled in
/// oblique::testing_raster for float and double (the rasterizer draws in float32).
inline namespace OBLIQUE_EIGEN_LAYOUT {
template <class T>
void check_on_rasterizer(const Implementation<T>& impl, const Contract& contract = Contract{},
                         const RasterSettings& settings = RasterSettings{});
}  // namespace OBLIQUE_EIGEN_LAYOUT

}  // namespace oblique::testing

/// A GoogleTest test that draws `implementation`'s answers (oblique::adapt()) to cases of
/// `contract` on the rasterizer (check_on_rasterizer()).
#define OBLIQUE_RASTER_TEST(Suite, Name, implementation, contract)         \
  TEST(Suite, Name) {                                                      \
    ::oblique::testing::check_on_rasterizer((implementation), (contract)); \
  }
