// The fuzz driver on the campaign's float engine: each input is judged for the three conventions'
// functions (the driver decodes the input once per function, in its convention). libFuzzer with
// clang; with fuzzing_replay, files or `--random N` mutated inputs (replay_main.cpp).
#include <oblique/fuzzing.h>

#include "float_engine.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using oblique::Convention;
  using oblique::Layout;
  namespace fa = oblique::false_alarms;
  // The closed form is given the perspective-shape inputs only (the rest are skipped).
  static const auto gl =
      oblique::adapt<float>("make_oblique_gl", Layout::column_major, fa::make_oblique_gl,
                            oblique::perspective_shape_only<float>);
  static const auto zero_one =
      oblique::adapt<float>("make_oblique_zero_one", Layout::column_major,
                            fa::make_oblique_zero_one, oblique::perspective_shape_only<float>);
  static const auto reversed_z =
      oblique::adapt<float>("make_oblique_reversed_z", Layout::column_major,
                            fa::make_oblique_reversed_z, oblique::perspective_shape_only<float>);
  static const auto for_convention = [](Convention convention) {
    oblique::fuzzing::Options options;
    options.conventions = {convention};
    return options;
  };
  static const oblique::fuzzing::Options options[] = {for_convention(Convention::gl),
                                                      for_convention(Convention::zero_one),
                                                      for_convention(Convention::reversed_z)};
  oblique::fuzzing::test_one_input(data, size, gl, options[0]);
  oblique::fuzzing::test_one_input(data, size, zero_one, options[1]);
  oblique::fuzzing::test_one_input(data, size, reversed_z, options[2]);
  return 0;
}
