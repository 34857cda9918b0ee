// A libFuzzer target for the engine's make_oblique: the project's decoder and exact judgement.
// clang++ -fsanitize=fuzzer,address; or link oblique::fuzzing_replay to replay inputs.
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
