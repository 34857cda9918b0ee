// The layout of Eigen's fixed-size matrices in this file, as a namespace name. Eigen aligns them
// to EIGEN_MAX_STATIC_ALIGN_BYTES, which follows the SIMD flags (16 bytes with SSE, 32 with AVX,
// 64 with AVX-512), so a struct holding a matrix after a smaller member (an Answer, a
// generated case) is laid out differently in files built with other flags. The compiled
// libraries' functions that take such structs are declared in an inline namespace of this name:
// a file whose layout is not the library's gets a link error that names both (eigen_align32
// against eigen_align16), never answers read at the wrong offsets. Build the file with the
// library's SIMD flags, or build the library with the file's.
#pragma once

#include <Eigen/Core>

#define OBLIQUE_EIGEN_LAYOUT_NAME(bytes) eigen_align##bytes
#define OBLIQUE_EIGEN_LAYOUT_OF(bytes) OBLIQUE_EIGEN_LAYOUT_NAME(bytes)
/// eigen_align16, eigen_align32, ...: the inline namespace of the compiled interfaces.
#define OBLIQUE_EIGEN_LAYOUT OBLIQUE_EIGEN_LAYOUT_OF(EIGEN_MAX_STATIC_ALIGN_BYTES)
