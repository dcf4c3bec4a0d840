#pragma once
// The one definition of a spring (docs/model.md section 2): a family's offset on the grid, with
// its stiffness and rest length. Everything else that describes springs is derived from it: the
// quantities below, which the force kernel streams through, and the flat listing of
// spring_list.hpp. The SIMD kernel includes this header in a translation unit compiled with
// -mavx (spring_kernel_impl.hpp), so it includes nothing (no Eigen, no standard library), and
// its member functions are integer arithmetic only: a copy the AVX unit emits of one of them
// holds no AVX instruction, whichever copy the linker keeps.
namespace drape {

/// The spring families of docs/model.md section 2.
enum class SpringFamily : unsigned char { structural, shear, bending };

/// One spring family's offset as a stencil on the grid: spring (r, c) joins particle (r, c) to
/// (r + dr, c + dc) wherever both are on the grid; dr >= 0, so the springs start in rows
/// 0 .. end_row - 1 and columns first_col .. end_col - 1. Its springs share stiffness and rest
/// length (the offset's length on the initial grid), and the springs of one grid row join two
/// contiguous runs of particles, which the force loop streams through.
struct SpringStencil {
  int dr = 0;
  int dc = 0;
  double stiffness = 0.0;
  double rest = 0.0;
  SpringFamily family = SpringFamily::structural;

  /// Both ends in one grid row: the runs of a row overlap.
  bool along_row() const { return dr == 0; }
  /// Index of a spring's second particle minus its first's, on a grid of `cols` columns.
  long offset(int cols) const { return static_cast<long>(dr) * cols + dc; }
  int first_col() const { return dc < 0 ? -dc : 0; }
  int end_col(int cols) const { return dc > 0 ? cols - dc : cols; }
  int end_row(int rows) const { return rows - dr; }
  /// Springs of one row (none when not positive: the offset is wider than the grid).
  long count(int cols) const { return end_col(cols) - first_col(); }
};

}  // namespace drape
