// The mistake: the far corner's x sign written as sgn(C_x) on the perspective matrices the
// engine's cameras make. There C'_x = C_x / M11, so this is sgn(C'_x) as long as M11 > 0; a
// mirror camera made by negating M11 (clip x flipped) gets the far corner on the wrong side in x,
// and the far plane cuts through the view volume. The engine knew about Vulkan's y flip: the y
// sign is taken from C' and is right.
#include "lengyel.h"

int main(int argc, char** argv) {
  return lengyel::serve(argc, argv, lengyel::Mistake::ignores_m11_sign);
}
