// A numerical fault, the formulas right: reversed Z computed by the [0, 1] routine on the matrix
// turned into a [0, 1] one (row 3 M_4 - M_3, formed in T) and flipped back. In float the far
// corner is lost for a large far / near ratio.
#include "lengyel.h"

int main(int argc, char** argv) {
  return lengyel::serve(argc, argv, lengyel::Mistake::reversed_z_through_zero_one);
}
