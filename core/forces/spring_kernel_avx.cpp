// spring_kernel.hpp's kernel in AVX packets. This file alone is compiled with -mavx; it
// includes nothing with external linkage that other files could share (see
// spring_kernel_impl.hpp).
#include "core/forces/spring_kernel_impl.hpp"

namespace drape::spring_kernel {

void add_avx(const SpringStencil& stencil, int rows, int cols, double c, const Arrays& arrays) {
  add_stencil<__m256d>(stencil, rows, cols, c, arrays);
}

void store_avx(const SpringStencil& stencil, int rows, int cols, double c, const Arrays& arrays,
               double* const spring_force[3], int row_begin, int row_end) {
  store_stencil<__m256d>(stencil, rows, cols, c, arrays, spring_force, row_begin, row_end);
}

}  // namespace drape::spring_kernel
