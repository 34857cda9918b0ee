// The mistake: sgn(x) computed as x / |x|, which is NaN when a component of C' is zero (a plane
// parallel to a frustum edge), so the whole third row becomes NaN.
#include "lengyel.h"

int main(int argc, char** argv) {
  return lengyel::serve(argc, argv, lengyel::Mistake::sign_by_division);
}
