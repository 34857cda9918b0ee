// The mistake: no check that the camera is behind the plane (C_w < 0). For a camera in front of
// the surface it returns a matrix anyway, which clips the wrong side or nothing at all.
#include "lengyel.h"

int main(int argc, char** argv) {
  return lengyel::serve(argc, argv, lengyel::Mistake::no_camera_guard);
}
