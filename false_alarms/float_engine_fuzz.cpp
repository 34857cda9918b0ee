// The fuzz driver on the campaign's float engine: each input is judged for the three conventions'
// functions and the [0, 1] one made through GL's (the driver decodes the input once per function,
// in its convention). libFuzzer with clang; with fuzzing_replay, files or `--random N` mutated
// inputs (replay_main.cpp).
#include <oblique/fuzzing.h>

#include "float_engine.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using oblique::Convention;
  using oblique::Layout;
  namespace fa = oblique::false_alarms;
  // The closed form is given the perspective-shape inputs only (the rest are skipped); each
  // function serves one convention, so the default contract judges it in that one.
  static const auto gl =
      oblique::adapt<float>("make_oblique_gl", Layout::column_major, Convention::gl,
                            fa::make_oblique_gl, oblique::perspective_shape_only<float>);
  static const auto zero_one =
      oblique::adapt<float>("make_oblique_zero_one", Layout::column_major, Convention::zero_one,
                            fa::make_oblique_zero_one, oblique::perspective_shape_only<float>);
  static const auto reversed_z =
      oblique::adapt<float>("make_oblique_reversed_z", Layout::column_major, Convention::reversed_z,
                            fa::make_oblique_reversed_z, oblique::perspective_shape_only<float>);
  static const auto zero_one_from_gl = oblique::adapt<float>(
      "make_oblique_zero_one_from_gl", Layout::column_major, Convention::zero_one,
      fa::make_oblique_zero_one_from_gl, oblique::perspective_shape_only<float>);
  oblique::fuzzing::test_one_input(data, size, gl);
  oblique::fuzzing::test_one_input(data, size, zero_one_from_gl);
  oblique::fuzzing::test_one_input(data, size, zero_one);
  oblique::fuzzing::test_one_input(data, size, reversed_z);
  return 0;
}
