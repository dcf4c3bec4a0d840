#pragma once
// The body of spring_kernel.hpp's kernels, included by one source file per instruction set. It
// uses GCC/Clang vector extensions, so the same lines compile to SSE2 or AVX packets. Everything
// here has internal linkage: the copies compiled with different instruction sets must never be
// merged by the linker.
#include <cstring>
#include <immintrin.h>

#include "core/forces/spring_kernel.hpp"

namespace drape::spring_kernel {
namespace {

// Must equal degenerate_length in forces.hpp (checked in grid_spring_forces.cpp).
constexpr double kernel_degenerate_length = 1e-12;

template <class V>
inline V load(const double* p) {
  V value;
  std::memcpy(&value, p, sizeof value);
  return value;
}

template <class V>
inline void store(double* p, V value) {
  std::memcpy(p, &value, sizeof value);
}

inline double square_root(double value) { return __builtin_sqrt(value); }
inline __m128d square_root(__m128d value) { return _mm_sqrt_pd(value); }
#ifdef __AVX__
inline __m256d square_root(__m256d value) { return _mm256_sqrt_pd(value); }
#endif

// Springs e .. e + width - 1 of the run from (i, j): forces into `row_force` at e (`buffered`)
// or straight onto the particles. One square root and one division a spring.
template <class V, bool damped, bool buffered>
inline void add_springs(const Arrays& a, double k, double rest, double c, long i, long j,
                        long e) {
  V d[3];
  for (int m = 0; m < 3; ++m) d[m] = load<V>(a.x[m] + j) - load<V>(a.x[m] + i);
  const V length = square_root(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  const V inverse_length = 1.0 / length;
  V magnitude = k * (length - rest);
  if constexpr (damped) {
    V w_dot_d = (load<V>(a.v[0] + j) - load<V>(a.v[0] + i)) * d[0];
    w_dot_d += (load<V>(a.v[1] + j) - load<V>(a.v[1] + i)) * d[1];
    w_dot_d += (load<V>(a.v[2] + j) - load<V>(a.v[2] + i)) * d[2];
    magnitude += c * w_dot_d * inverse_length;
  }
  const V scale_if_defined = magnitude * inverse_length;
  const V scale = length < kernel_degenerate_length ? V{} : scale_if_defined;
  for (int m = 0; m < 3; ++m) {
    const V force = scale * d[m];
    if constexpr (buffered) {
      store(a.row_force[m] + e, force);
    } else {
      store(a.force[m] + i, load<V>(a.force[m] + i) + force);
      store(a.force[m] + j, load<V>(a.force[m] + j) - force);
    }
  }
}

// The springs e = 0 .. count - 1 of the run from (i, j), in packets and then one by one.
template <class V, bool damped, bool buffered>
inline void add_run(const SpringStencil& s, long count, double c, const Arrays& a, long i,
                    long j) {
  constexpr long width = sizeof(V) / sizeof(double);
  long e = 0;
  for (; e + width <= count; e += width)
    add_springs<V, damped, buffered>(a, s.stiffness, s.rest, c, i + e, j + e, e);
  for (; e < count; ++e)
    add_springs<double, damped, buffered>(a, s.stiffness, s.rest, c, i + e, j + e, e);
}

// Springs along a row join overlapping runs: adding a packet's forces to both
// would store and reload half-overlapping packets, which stalls store forwarding, so their
// forces are added after the row.
template <class V, bool damped, bool buffered>
inline void add_rows(const SpringStencil& s, int rows, int cols, double c, const Arrays& a) {
  const long offset = s.offset(cols), first = s.first_col(), count = s.count(cols);
  const int end_row = s.end_row(rows);
  for (int r = 0; r < end_row; ++r) {
    const long i = static_cast<long>(r) * cols + first, j = i + offset;
    add_run<V, damped, buffered>(s, count, c, a, i, j);
    if constexpr (buffered) {
      for (int m = 0; m < 3; ++m) {
        for (long e = 0; e < count; ++e) a.force[m][i + e] += a.row_force[m][e];
        for (long e = 0; e < count; ++e) a.force[m][j + e] -= a.row_force[m][e];
      }
    }
  }
}

// The force on i of every spring of rows [row_begin, row_end) into spring_force at i.
template <class V, bool damped>
inline void store_rows(const SpringStencil& s, int rows, int cols, double c, const Arrays& a,
                       double* const spring_force[3], int row_begin, int row_end) {
  const long offset = s.offset(cols), first = s.first_col(), count = s.count(cols);
  const int end_row = s.end_row(rows);
  Arrays row = a;
  for (int r = row_begin; r < row_end && r < end_row; ++r) {
    const long i = static_cast<long>(r) * cols + first;
    for (int m = 0; m < 3; ++m) row.row_force[m] = spring_force[m] + i;
    add_run<V, damped, true>(s, count, c, row, i, i + offset);
  }
}

template <class V>
inline void store_stencil(const SpringStencil& s, int rows, int cols, double c, const Arrays& a,
                          double* const spring_force[3], int row_begin, int row_end) {
  if (c != 0.0)
    store_rows<V, true>(s, rows, cols, c, a, spring_force, row_begin, row_end);
  else
    store_rows<V, false>(s, rows, cols, c, a, spring_force, row_begin, row_end);
}

template <class V>
inline void add_stencil(const SpringStencil& s, int rows, int cols, double c, const Arrays& a) {
  if (c != 0.0)
    s.along_row() ? add_rows<V, true, true>(s, rows, cols, c, a)
                  : add_rows<V, true, false>(s, rows, cols, c, a);
  else
    s.along_row() ? add_rows<V, false, true>(s, rows, cols, c, a)
                  : add_rows<V, false, false>(s, rows, cols, c, a);
}

}  // namespace
}  // namespace drape::spring_kernel
