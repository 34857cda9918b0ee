// The mistake: the Direct3D/Vulkan [0, 1] formulas (a = 1 / (C . Q), M'_3 = a C) applied to an
// OpenGL [-1, 1] matrix. The near plane is then not C and the far plane misses Q.
#include "lengyel.h"

int main(int argc, char** argv) {
  return lengyel::serve(argc, argv, lengyel::Mistake::zero_one_factor_on_gl);
}
