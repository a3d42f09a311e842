#pragma once
// Rows of work on OpenMP threads, private to the library: the depth path's image blocks and median filter
// (perception/depth_scene.cpp), a scene's objects completed (perception/completion.cpp), the join rule's pairs
// (perception/occlusion_merge.cpp), the collision experts of a scene (grasp/scene_synthesis.cpp).
#include <cstddef>
#include <cstdint>
#include <exception>
#include <vector>

namespace graspmix::detail {

/// How rows go to threads: in equal blocks of consecutive rows (many rows of about equal work: an image's), or one
/// at a time as threads come free (a few rows of unequal work, the largest first: a scene's objects).
enum class RowOrder { Blocks, AsThreadsFree };

/// A State for rows that need none.
struct NoState {};

/// Calls work(state, i) for every row i in [0, n) on OpenMP threads, each thread with a State of its own
/// (default-constructed: its buffers, made once and reused row after row). No exception may leave an OpenMP region:
/// what a row throws is kept, and the lowest such row's exception is rethrown once all are done.
template <class State, class Work>
void parallel_rows(std::int64_t n, Work&& work, RowOrder order = RowOrder::Blocks) {
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(n));
  const auto row = [&](State& state, std::int64_t i) {
    try {
      work(state, i);
    } catch (...) {
      errors[static_cast<std::size_t>(i)] = std::current_exception();
    }
  };
  if (n == 1) {  // one row runs here: its own parallel loops, if any, keep the threads
    State state{};
    row(state, 0);
  } else {
#pragma omp parallel
    {
      State state{};
      if (order == RowOrder::Blocks) {
#pragma omp for schedule(static)
        for (std::int64_t i = 0; i < n; ++i) row(state, i);
      } else {
#pragma omp for schedule(dynamic, 1)
        for (std::int64_t i = 0; i < n; ++i) row(state, i);
      }
    }
  }
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace graspmix::detail
