// An engine's oblique clipping as engines ship it: no guards and no statuses (callers never pass
// an input without an answer), so every request gets a matrix. Checked with --answers-only.
#include "lengyel.h"

int main(int argc, char** argv) {
  return lengyel::serve(argc, argv, lengyel::Mistake::no_statuses);
}
