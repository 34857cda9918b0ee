// A fuzz target for a user's consumers, as docs/fuzzing.md writes it, on two wrong ones of
// consumers.h (OpenGL's rows on any matrix; the reflected look-at): replayed over fuzz_consumers'
// corpus it must abort on the first, naming culling_near_is_c (CTest: consumers_fuzz_driver_*).
#include <oblique/fuzzing.h>

#include "consumers.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const oblique::Consumers<float> mine = [] {
    oblique::Consumers<float> c;
    c.name = "wrong_consumers";
    c.culling_planes = engine_consumers::gl_planes_on_any_matrix<float>;
    c.mirror_view = engine_consumers::mirror_by_reflected_look_at<float>;
    return c;
  }();
  return oblique::fuzzing::test_consumers(data, size, mine);
}
