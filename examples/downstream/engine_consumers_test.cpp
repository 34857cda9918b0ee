// The code around the engine's matrix: its depth reconstruction, checked by the consumer
// properties (oblique::Consumers, one adapter lambda) on the oblique matrices of its contract.
#include <oblique/testing.h>

#include "engine.h"

namespace {

oblique::Consumers<float> engine_consumers() {
  oblique::Consumers<float> c;
  c.name = "engine::view_position";
  c.view_position = [](const oblique::oracle::DepthSample<float>& s) {
    float m[16], out[3];
    for (int r = 0; r < 4; ++r)
      for (int k = 0; k < 4; ++k) m[4 * k + r] = s.projection(r, k);  // column-major
    engine::view_position(m, s.ndc_x, s.ndc_y, s.depth, out);
    return oblique::Vector3<float>(out[0], out[1], out[2]);
  };
  return c;
}

// OpenGL depth, the perspective shapes the engine builds.
const oblique::Contract engine_contract = oblique::read_contract(R"({
  "families": ["perspective", "off_axis", "infinite", "y_flipped", "jittered"],
  "conventions": ["gl"]
})")
                                              .value();

}  // namespace

OBLIQUE_CONSUMERS_TEST(Engine, depthReconstructionIsRight, engine_consumers(), engine_contract)
