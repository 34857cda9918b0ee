// A libFuzzer target for the engine's make_oblique: the project's decoder and exact judgement.
// clang++ -fsanitize=fuzzer,address; or link oblique::fuzzing_replay to replay inputs.
#include <oblique/fuzzing.h>

#include "engine.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // OpenGL depth, the perspective shape its closed form reads; the default contract.
  static const auto make_oblique =
      oblique::adapt<float>("make_oblique", oblique::Layout::column_major, oblique::Convention::gl,
                            engine::make_oblique, oblique::perspective_shape_only<float>);
  return oblique::fuzzing::test_one_input(data, size, make_oblique);
}
