// The mistake: the far corner's x and y signs taken from the camera-space plane C instead of the
// clip-space plane C' = M^-T C. Right for the standard symmetric perspective matrix (where the
// signs agree), wrong for off-axis, flipped, rotated and general ones.
#include "lengyel.h"

int main(int argc, char** argv) {
  return lengyel::serve(argc, argv, lengyel::Mistake::camera_space_signs);
}
