// Two mistakes in one program: no C_w < 0 check (no_camera_guard) and sgn(x) = x / |x|
// (sign_by_division). Verify stops at the first; --keep-going reports both.
#include "lengyel.h"

int main(int argc, char** argv) {
  return lengyel::serve(argc, argv, lengyel::Mistake::two_bugs);
}
