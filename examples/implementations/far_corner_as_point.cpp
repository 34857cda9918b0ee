// A numerical fault, the formulas right: the far corner taken as a point Q / Q_w (unprojected to
// camera space) and a = k (M_4 . Q) / (C . Q) on it; an infinite far plane has Q_w = 0.
#include "lengyel.h"

int main(int argc, char** argv) {
  return lengyel::serve(argc, argv, lengyel::Mistake::far_corner_as_point);
}
