#pragma once
// The spring loop's kernel: the forces of one spring stencil (spring_stencil.hpp) of a rows x
// cols grid on structure-of-arrays positions and velocities. Written once
// (spring_kernel_impl.hpp) and compiled for two instruction sets, SSE2 (every x86-64) and AVX
// (four doubles a packet, chosen at run time when the processor has it). Both give the same
// bits: every operation is an IEEE add, multiply, divide or square root, lane by lane, and no
// multiply-add is contracted. It includes no Eigen (see spring_stencil.hpp).
#include "core/cloth/spring_stencil.hpp"

namespace drape::spring_kernel {

/// Component arrays (x, y, z) of the N = rows x cols particles. `row_force` holds cols values a
/// component.
struct Arrays {
  const double* x[3];
  const double* v[3];
  double* force[3];
  double* row_force[3];
};

/// Adds the stencil's elastic and damping (coefficient c; velocities unread when 0) forces to
/// `force`: on i the force k (L - L0) u + c (w . u) u with d = x_j - x_i, u = d / L,
/// w = v_j - v_i, and the opposite on j; zero below degenerate_length (forces.hpp).
void add_sse2(const SpringStencil& stencil, int rows, int cols, double c, const Arrays& arrays);
/// The same with AVX packets; call only when has_avx().
void add_avx(const SpringStencil& stencil, int rows, int cols, double c, const Arrays& arrays);
/// The force on i of each spring of rows [row_begin, row_end), as add_sse2 computes it, stored
/// into spring_force (3 component arrays of N) at i; the threaded force loop adds them up per
/// particle afterwards (grid_spring_forces.hpp).
void store_sse2(const SpringStencil& stencil, int rows, int cols, double c, const Arrays& arrays,
                double* const spring_force[3], int row_begin, int row_end);
/// The same with AVX packets; call only when has_avx().
void store_avx(const SpringStencil& stencil, int rows, int cols, double c, const Arrays& arrays,
               double* const spring_force[3], int row_begin, int row_end);
/// Whether this processor runs add_avx and store_avx.
bool has_avx();

}  // namespace drape::spring_kernel
