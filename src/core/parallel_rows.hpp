#pragma once
// Rows of work on OpenMP threads, private to the library: the depth path's image blocks and median filter
// (perception/depth_scene.cpp).
#include <cstddef>
#include <cstdint>
#include <exception>
#include <vector>

namespace graspmix::detail {

/// Calls work(state, i) for every row i in [0, n) on OpenMP threads (a static schedule), each thread with a State
/// of its own (default-constructed: its buffers, made once and reused row after row). No exception may leave an
/// OpenMP region: what a row throws is kept, and the lowest such row's exception is rethrown once all are done.
template <class State, class Work>
void parallel_rows(std::int64_t n, Work&& work) {
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(n));
#pragma omp parallel
  {
    State state{};
#pragma omp for schedule(static)
    for (std::int64_t i = 0; i < n; ++i) {
      try {
        work(state, i);
      } catch (...) {
        errors[static_cast<std::size_t>(i)] = std::current_exception();
      }
    }
  }
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace graspmix::detail
