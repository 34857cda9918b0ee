// libFuzzer target for the user-facing fuzz driver: oblique::fuzzing::test_one_input on an
// engine-style float function, exactly as README's "Fuzz target" example writes it. The function
// is examples/downstream's engine::make_oblique (column-major, OpenGL, refuses by returning
// false), the fixed one (ENGINE_FIXED=1), so a violation here is the harness's false alarm. It is
// not one of scripts/fuzz.sh's targets (fuzz_*.cpp: it fuzzes an example, not the project); it is
// here to measure what the driver costs a user (docs/fuzzing.md), and CTest replays the
// fuzz_oblique corpus through it (engine_driver_replay).
#include <oblique/fuzzing.h>

#include "engine.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const auto make_oblique =
      oblique::adapt<float>("make_oblique", oblique::Layout::column_major, engine::make_oblique,
                            oblique::perspective_shape_only<float>);
  oblique::fuzzing::Options options;
  options.conventions = {oblique::Convention::gl};
  return oblique::fuzzing::test_one_input(data, size, make_oblique, options);
}
