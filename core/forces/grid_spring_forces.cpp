#include "core/forces/grid_spring_forces.hpp"

#include "core/forces/forces.hpp"
#include "core/forces/spring_kernel_impl.hpp"

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

spring_kernel::Arrays kernel_arrays(ConstComponents x, ConstComponents v, Components force,
                                    Components row_force) {
  return {{x.col(0).data(), x.col(1).data(), x.col(2).data()},
          {v.col(0).data(), v.col(1).data(), v.col(2).data()},
          {&force(0, 0), &force(0, 1), &force(0, 2)},
          {&row_force(0, 0), &row_force(0, 1), &row_force(0, 2)}};
}

namespace {

// Column stride: the rows rounded up to a page (512 doubles), plus 256 bytes, so that column k
// starts 256 k bytes further into its page (16 columns before the offsets repeat).
Eigen::Index staggered_stride(Eigen::Index rows) {
  constexpr Eigen::Index page = 512, shift = 32;
  return (rows + page - 1) / page * page + shift;
}

}  // namespace

StaggeredColumns::StaggeredColumns(Eigen::Index rows, Eigen::Index groups)
    : m_rows(rows), m_buffer(staggered_stride(rows), 3 * groups) {}

Components StaggeredColumns::group(Eigen::Index k) {
  return Eigen::Map<Eigen::ArrayX3d, 0, Eigen::OuterStride<>>(
      &m_buffer(0, 3 * k), m_rows, 3, Eigen::OuterStride<>(m_buffer.rows()));
}

GridSpringForces::GridSpringForces(const Cloth& cloth)
    : m_columns(cloth.size(), 3),
      m_row_force(cloth.params.cols, 3),
      m_add(spring_kernel::has_avx() ? spring_kernel::add_avx : spring_kernel::add_sse2) {
  for (const SpringStencil& s : cloth.stencils)
    m_stencils.push_back(kernel_stencil(s, cloth.params.rows, cloth.params.cols));
}

ConstComponents GridSpringForces::evaluate(ConstVecRef x, ConstVecRef v, double c) {
  Components xs = m_columns.group(0), vs = m_columns.group(1), force = m_columns.group(2);
  to_components(x, xs);
  if (c != 0.0) to_components(v, vs);
  force.setZero();
  const spring_kernel::Arrays arrays = kernel_arrays(xs, vs, force, m_row_force);
  for (const spring_kernel::Stencil& s : m_stencils) m_add(s, c, arrays);
  return force;
}

}  // namespace drape
