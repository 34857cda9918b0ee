// One test name in two executables (tests/CMakeLists.txt builds this file twice): with
// SAME_NAMES_WRONG the function drops the off-axis terms and fails with a report; without, it is
// the core's and passes. Run one after the other into one reports folder, the passing one must
// leave the failing one's report where it is (reports are keyed by executable and test).
#include "oblique/mistakes/mistakes.h"
#include "oblique/oblique.h"
#include "oblique/testing.h"

namespace {

#if SAME_NAMES_WRONG
const auto function = oblique::mistakes::mistaken_implementation<double>(
    {oblique::mistakes::Mistake::drops_off_axis});
#else
const auto function =
    oblique::adapt<double>("core", oblique::Layout::row_major,
                           [](const oblique::Matrix4<double>& m, const oblique::Vector4<double>& c,
                              oblique::Convention k) { return oblique::apply<double>(m, c, k); });
#endif

}  // namespace

OBLIQUE_PROPERTY_TEST(SameNames, oneTestInTwoExecutables, function,
                      oblique::read_contract(R"({"families": ["off_axis"],
                                                 "properties": ["far_plane_through_corner"]})")
                          .value())
