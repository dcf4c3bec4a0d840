#pragma once
// The hot loops' threads (docs/performance/threads.md): one setting for the process and a loop
// over contiguous blocks of items. Every caller's items write only their own outputs (a gather
// per particle, never a scatter into another item's), so the result does not depend on how the
// items are split among threads: the same bits for any number of them.
#include <cstddef>
#include <type_traits>
#include <utility>

namespace drape {

/// The hot loops' thread count: at least 1; all of the process's processors until set.
int thread_count();
/// Sets the thread count (n >= 1).
void set_thread_count(int n);
/// The processors this process may run on (OpenMP's omp_get_num_procs: the affinity mask).
int available_processors();

/// Particles from which the per-particle loops (forces, updates) run on threads: below it
/// starting the threads costs more than they save (docs/performance/threads.md).
inline constexpr std::ptrdiff_t threaded_particles_from = 2048;

/// Whether parallel_for(n, serial_below, ...) runs on more than one thread.
inline bool runs_threaded(std::ptrdiff_t n, std::ptrdiff_t serial_below) {
  return thread_count() > 1 && n >= 2 && n >= serial_below;
}

namespace detail {

/// A non-owning reference to a callable void(std::ptrdiff_t begin, std::ptrdiff_t end).
class BlockBody {
 public:
  template <class F, class = std::enable_if_t<!std::is_same_v<std::decay_t<F>, BlockBody>>>
  BlockBody(F& f)  // NOLINT(google-explicit-constructor): a view of the caller's lambda
      : m_object(const_cast<void*>(static_cast<const void*>(&f))),
        m_call([](void* o, std::ptrdiff_t b, std::ptrdiff_t e) { (*static_cast<F*>(o))(b, e); }) {}
  void operator()(std::ptrdiff_t begin, std::ptrdiff_t end) const { m_call(m_object, begin, end); }

 private:
  void* m_object;
  void (*m_call)(void*, std::ptrdiff_t, std::ptrdiff_t);
};

void parallel_blocks(std::ptrdiff_t n, std::ptrdiff_t serial_below, BlockBody body);

}  // namespace detail

/// Calls body(begin, end) on contiguous blocks covering [0, n), one block a thread of
/// thread_count() (OpenMP, static schedule), or body(0, n) on the calling thread when n is below
/// `serial_below` (where starting threads costs more than they save, measured in
/// docs/performance/threads.md) or one thread is set. The body must write only the outputs of its
/// own items and must not throw.
template <class Body>
void parallel_for(std::ptrdiff_t n, std::ptrdiff_t serial_below, Body&& body) {
  detail::parallel_blocks(n, serial_below, detail::BlockBody(body));
}

}  // namespace drape
