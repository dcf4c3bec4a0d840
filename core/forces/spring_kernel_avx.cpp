// spring_kernel.hpp's kernel in AVX packets. This file alone is compiled with -mavx; it
// includes nothing with external linkage that other files could share (see
// spring_kernel_impl.hpp).
#include "core/forces/spring_kernel_impl.hpp"

namespace drape::spring_kernel {

void add_avx(const Stencil& stencil, double c, const Arrays& arrays) {
  add_stencil<__m256d>(stencil, c, arrays);
}

}  // namespace drape::spring_kernel
