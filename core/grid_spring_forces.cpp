#include "core/grid_spring_forces.hpp"

#include "core/forces.hpp"
#include "core/spring_kernel_impl.hpp"

namespace drape {

namespace spring_kernel {

static_assert(kernel_degenerate_length == degenerate_length);

void add_sse2(const Stencil& stencil, double c, const Arrays& arrays) {
  add_stencil<__m128d>(stencil, c, arrays);
}

bool has_avx() {
  // cpu_init first: this may run before libgcc's own initialiser (static construction).
  static const bool avx = (__builtin_cpu_init(), __builtin_cpu_supports("avx"));
  return avx;
}

}  // namespace spring_kernel

spring_kernel::Stencil kernel_stencil(const SpringStencil& stencil, int rows, int cols) {
  spring_kernel::Stencil k;
  k.along_row = stencil.dr == 0;
  k.offset = static_cast<long>(stencil.dr) * cols + stencil.dc;
  k.first = stencil.first_col();
  k.count = stencil.end_col(cols) - stencil.first_col();
  k.rows = rows - stencil.dr;
  k.cols = cols;
  k.stiffness = stencil.stiffness;
  k.rest = stencil.rest;
  return k;
}

spring_kernel::Arrays kernel_arrays(const Eigen::ArrayX3d& x, const Eigen::ArrayX3d& v,
                                    Eigen::ArrayX3d& force, Eigen::ArrayX3d& row_force) {
  return {{&x(0, 0), &x(0, 1), &x(0, 2)},
          {&v(0, 0), &v(0, 1), &v(0, 2)},
          {&force(0, 0), &force(0, 1), &force(0, 2)},
          {&row_force(0, 0), &row_force(0, 1), &row_force(0, 2)}};
}

GridSpringForces::GridSpringForces(const Cloth& cloth)
    : m_x(cloth.size(), 3),
      m_v(cloth.size(), 3),
      m_force(cloth.size(), 3),
      m_row_force(cloth.params.cols, 3),
      m_add(spring_kernel::has_avx() ? spring_kernel::add_avx : spring_kernel::add_sse2) {
  for (const SpringStencil& s : cloth.stencils)
    m_stencils.push_back(kernel_stencil(s, cloth.params.rows, cloth.params.cols));
}

const Eigen::ArrayX3d& GridSpringForces::evaluate(ConstVecRef x, ConstVecRef v, double c) {
  to_components(x, m_x);
  if (c != 0.0) to_components(v, m_v);
  m_force.setZero();
  const spring_kernel::Arrays arrays = kernel_arrays(m_x, m_v, m_force, m_row_force);
  for (const spring_kernel::Stencil& s : m_stencils) m_add(s, c, arrays);
  return m_force;
}

}  // namespace drape
