#pragma once
// The spring loop of the force evaluation (docs/model.md section 4, elastic force and spring damping), stencil by
// stencil on a structure-of-arrays copy of the state. The springs of one stencil in one grid row
// join two contiguous runs of particles, so the kernel (spring_kernel.hpp) streams through
// contiguous memory in packed SIMD, square roots and divisions included, with no gather or
// scatter of 3-vectors.
#include <cstddef>
#include <vector>

#include "core/cloth/cloth.hpp"
#include "core/forces/spring_kernel.hpp"
#include "core/state/state.hpp"

namespace drape {

/// N x 3 components (column k: component k of every particle), possibly columns of a larger
/// buffer.
using Components = Eigen::Ref<Eigen::ArrayX3d, 0, Eigen::OuterStride<>>;
using ConstComponents = Eigen::Ref<const Eigen::ArrayX3d, 0, Eigen::OuterStride<>>;

/// Interleaved 3N values (x0 y0 z0 x1 ...) into N x 3 components, the kernel's layout.
inline void to_components(ConstVecRef interleaved, Components out) {
  out = Eigen::Map<const Eigen::Matrix3Xd>(interleaved.data(), 3, interleaved.size() / 3)
            .transpose();
}

/// Groups of N x 3 components in one buffer, each column starting at a different offset
/// within the 4 KiB page. Columns a multiple of 4 KiB apart (N = 4096, or separate allocations,
/// which the allocator aligns alike) alias in the low address bits that the processor uses to
/// match loads with earlier stores, and such a load then waits for the store: the force
/// evaluation at 64 x 64 ran 15 to 18 % slower, depending on where the arrays had landed.
class StaggeredColumns {
 public:
  StaggeredColumns(Eigen::Index rows, Eigen::Index groups);
  /// Group k: columns 3k, 3k + 1, 3k + 2.
  Components group(Eigen::Index k);
  Eigen::Index groups() const { return m_buffer.cols() / 3; }

 private:
  Eigen::Index m_rows;
  Eigen::ArrayXXd m_buffer;
};

/// The kernel's view of N x 3 arrays (`row_force`: cols x 3).
spring_kernel::Arrays kernel_arrays(ConstComponents x, ConstComponents v, Components force,
                                    Components row_force);

/// Spring forces of a grid cloth into an N x 3 array (column k: component k of every particle).
///
/// On one thread each spring adds its force to both particles, stencil by stencil and row by
/// row. On several, each spring's force is first stored at its first particle, then every
/// particle gathers its springs' forces in that very order (per stencil: a spring along a row
/// adds before the one ending there subtracts; across rows the spring from the row above
/// subtracts first), so the sums, and the bits, are the same for any number of threads.
class GridSpringForces {
 public:
  explicit GridSpringForces(const Cloth& cloth);

  /// Elastic plus damping (coefficient c) forces of every spring at (x, v), summed per
  /// particle. With c = 0 the velocities are not read. The result lives until the next call.
  ConstComponents evaluate(ConstVecRef x, ConstVecRef v, double c);

 private:
  using Add = void (*)(const SpringStencil&, int, int, double, const spring_kernel::Arrays&);
  using Store = void (*)(const SpringStencil&, int, int, double, const spring_kernel::Arrays&,
                         double* const[3], int, int);
  void evaluate_threaded(double c, const spring_kernel::Arrays& arrays);
  // Grid rows [row_begin, row_end) of `force`: each particle's springs from m_spring_columns.
  void gather_rows(int row_begin, int row_end, const spring_kernel::Arrays& arrays);

  int m_rows, m_cols;
  std::vector<SpringStencil> m_stencils;
  StaggeredColumns m_columns;   // x, v, force
  Eigen::ArrayX3d m_row_force;  // one row of springs, for stencils along rows
  StaggeredColumns m_spring_columns;  // threaded: each stencil's spring forces; empty until then
  Add m_add;
  Store m_store;
};

}  // namespace drape
