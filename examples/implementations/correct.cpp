// Lengyel's oblique near plane, done right: signs of the clip-space plane C' = M^-T C, the far
// corner Q = M^-1 Q', the depth range of the request's convention, a guard for every input
// without an answer. `oblique verify` passes it in double, and with --float in float.
#include "lengyel.h"

int main(int argc, char** argv) {
  return lengyel::serve(argc, argv, lengyel::Mistake::none);
}
