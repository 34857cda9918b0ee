// The mistake: portal math written for a centred camera. A stereo eye (M14 != 0) or a lens shift
// (M24 != 0) is dropped when C' and the far corner Q are computed, so the far plane misses the
// far corner and a sliver of the view volume is clipped.
#include "lengyel.h"

int main(int argc, char** argv) {
  return lengyel::serve(argc, argv, lengyel::Mistake::ignores_shift);
}
