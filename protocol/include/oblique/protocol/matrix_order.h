// The order a program takes the 4x4 matrices of its requests and answers in. The protocol writes
// each as 16 numbers of M (acting on column vectors) by rows; a program may take them by columns
// instead: OpenGL's storage, and a row-vector engine's R = M^T by rows (Direct3D, DirectXMath),
// the same 16 numbers. `--layout` of verify and check names it as adapt()'s Layout does.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace oblique::protocol {

enum class MatrixOrder {
  rows,     ///< M by rows: the protocol's own order (--layout row_major, the default)
  columns,  ///< M by columns (--layout column_major, or row_vectors: R = M^T by rows)
};

/// The names `--layout` takes (adapt()'s Layout names).
inline constexpr const char* kLayoutNames[] = {"row_major", "column_major", "row_vectors"};

/// The order `--layout NAME` stands for: row_major, column_major or row_vectors; none otherwise.
std::optional<MatrixOrder> matrix_order_of_layout(std::string_view name);

/// `line` with every matrix in it put in the other order: each JSON array of exactly 16 elements
/// none of which is an array or an object (a 4x4 matrix: the protocol's only such array) is
/// transposed, its element tokens moved as they are written (numbers keep every digit). Putting
/// a line in the other order twice gives it back. Text that is not JSON is left as it is past the
/// point where it stops being so (its parser says why).
std::string other_matrix_order(std::string_view line);

/// `line` as a program in `order` is handed it, or writes it (the same map: a transpose).
inline std::string in_matrix_order(std::string_view line, MatrixOrder order) {
  return order == MatrixOrder::rows ? std::string(line) : other_matrix_order(line);
}

}  // namespace oblique::protocol
