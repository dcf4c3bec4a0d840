#include "core/forces/grid_spring_forces.hpp"

#include "core/forces/forces.hpp"
#include "core/forces/spring_kernel_impl.hpp"
#include "core/parallel/parallel_for.hpp"

namespace drape {

namespace spring_kernel {

static_assert(kernel_degenerate_length == degenerate_length);

void add_sse2(const SpringStencil& stencil, int rows, int cols, double c, const Arrays& arrays) {
  add_stencil<__m128d>(stencil, rows, cols, c, arrays);
}

void store_sse2(const SpringStencil& stencil, int rows, int cols, double c, const Arrays& arrays,
                double* const spring_force[3], int row_begin, int row_end) {
  store_stencil<__m128d>(stencil, rows, cols, c, arrays, spring_force, row_begin, row_end);
}

bool has_avx() {
  // cpu_init first: this may run before libgcc's own initialiser (static construction).
  static const bool avx = (__builtin_cpu_init(), __builtin_cpu_supports("avx"));
  return avx;
}

}  // namespace spring_kernel

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
    : m_rows(cloth.params.rows),
      m_cols(cloth.params.cols),
      m_stencils(cloth.stencils),
      m_columns(cloth.size(), 3),
      m_row_force(cloth.params.cols, 3),
      m_spring_columns(0, 0),
      m_add(spring_kernel::has_avx() ? spring_kernel::add_avx : spring_kernel::add_sse2),
      m_store(spring_kernel::has_avx() ? spring_kernel::store_avx : spring_kernel::store_sse2) {}

ConstComponents GridSpringForces::evaluate(ConstVecRef x, ConstVecRef v, double c) {
  Components xs = m_columns.group(0), vs = m_columns.group(1), force = m_columns.group(2);
  const spring_kernel::Arrays arrays = kernel_arrays(xs, vs, force, m_row_force);
  if (runs_threaded(static_cast<std::ptrdiff_t>(m_rows) * m_cols, threaded_particles_from)) {
    parallel_for(m_rows, 0, [&](std::ptrdiff_t begin, std::ptrdiff_t end) {
      const Eigen::Index first = begin * m_cols, count = (end - begin) * m_cols;
      to_components(x.segment(3 * first, 3 * count), xs.middleRows(first, count));
      if (c != 0.0) to_components(v.segment(3 * first, 3 * count), vs.middleRows(first, count));
    });
    evaluate_threaded(c, arrays);
    return force;
  }
  to_components(x, xs);
  if (c != 0.0) to_components(v, vs);
  force.setZero();
  for (const SpringStencil& s : m_stencils) m_add(s, m_rows, m_cols, c, arrays);
  return force;
}

void GridSpringForces::evaluate_threaded(double c, const spring_kernel::Arrays& arrays) {
  const auto stencils = static_cast<Eigen::Index>(m_stencils.size());
  if (m_spring_columns.groups() != stencils)
    m_spring_columns = StaggeredColumns(static_cast<Eigen::Index>(m_rows) * m_cols, stencils);
  parallel_for(m_rows, 0, [&](std::ptrdiff_t begin, std::ptrdiff_t end) {
    for (Eigen::Index k = 0; k < stencils; ++k) {
      Components out = m_spring_columns.group(k);
      double* const columns[3] = {&out(0, 0), &out(0, 1), &out(0, 2)};
      m_store(m_stencils[static_cast<std::size_t>(k)], m_rows, m_cols, c, arrays, columns,
              static_cast<int>(begin), static_cast<int>(end));
    }
  });
  parallel_for(m_rows, 0, [&](std::ptrdiff_t begin, std::ptrdiff_t end) {
    gather_rows(static_cast<int>(begin), static_cast<int>(end), arrays);
  });
}

void GridSpringForces::gather_rows(int row_begin, int row_end, const spring_kernel::Arrays& a) {
  for (int m = 0; m < 3; ++m) {
    double* force = a.force[m];
    const long begin = static_cast<long>(row_begin) * m_cols, end = static_cast<long>(row_end) * m_cols;
    std::fill(force + begin, force + end, 0.0);
    for (std::size_t k = 0; k < m_stencils.size(); ++k) {
      const SpringStencil& s = m_stencils[k];
      const long offset = s.offset(m_cols), first = s.first_col(), count = s.count(m_cols);
      const int end_row = s.end_row(m_rows);
      const double* spring = &m_spring_columns.group(static_cast<Eigen::Index>(k))(0, m);
      for (int r = row_begin; r < row_end; ++r) {
        const long row = static_cast<long>(r) * m_cols;
        const bool starts = r < end_row;
        const int from = r - s.dr;  // the row whose springs end in row r
        const bool ends = from >= 0 && from < end_row;
        // Spring e of a row starts at row + first + e and ends offset further on.
        const long i = row + first;
        if (s.along_row()) {
          if (!starts) continue;
          for (long e = 0; e < count; ++e) force[i + e] += spring[i + e];
          for (long e = 0; e < count; ++e) force[i + offset + e] -= spring[i + e];
          continue;
        }
        if (ends) {
          const long source = static_cast<long>(from) * m_cols + first;
          for (long e = 0; e < count; ++e) force[source + offset + e] -= spring[source + e];
        }
        if (starts)
          for (long e = 0; e < count; ++e) force[i + e] += spring[i + e];
      }
    }
  }
}

}  // namespace drape
