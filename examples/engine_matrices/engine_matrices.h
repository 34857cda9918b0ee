// Oblique-matrix functions as engines write them (docs/engines.md): each idiom a right function
// and a wrong twin, in the engine's own terms: float, its storage (column-major for OpenGL and
// Vulkan code, row vectors for Direct3D-style code: the transpose, stored by rows), its depth
// range and handedness, void (answers only). Written for oblique from the formulas; no engine's
// code is copied. idioms.txt lists them with what each claims and what names each twin.
//
// The plane is (a, b, c, d) in the camera's space, the side kept where a x + b y + c z + d > 0.
#pragma once

#include <string>
#include <vector>

namespace engine_matrices {

/// An engine's oblique function: the 16 numbers of its projection, modified in place.
using Function = void (*)(float m[16], const float plane[4]);

/// How an idiom stores its matrix (oblique::Layout's names).
enum class Storage { column_major, row_vectors };

struct Idiom {
  std::string name;  ///< e.g. "gl_listing"; its twin is name + "_wrong"
  Storage storage = Storage::column_major;
  Function right = nullptr, wrong = nullptr;
};

/// Every idiom, in the order of idioms.txt.
const std::vector<Idiom>& idioms();

/// The idiom called `name`, or its twin where `name` ends in "_wrong" (`*wrong` set); nullptr
/// for an unknown name.
const Idiom* find(const std::string& name, bool* wrong);

}  // namespace engine_matrices
