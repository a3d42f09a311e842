#pragma once
// A sorting network for a few values, private to the library: the depth path's block medians
// (perception/depth_scene.cpp) sort 16 depths per block of 4 x 4 pixels, 19,200 blocks an image.
#include <array>
#include <cstddef>
#include <utility>  // std::index_sequence

#ifdef __SSE2__
#include <emmintrin.h>
#endif

namespace graspmix::detail {

/// A comparator of a network: after it, the lesser of the two values is at `lo`, the greater at `hi`.
struct Comparator {
  std::size_t lo = 0, hi = 0;
};

/// Calls f(lo, hi) for each comparator of Batcher's odd-even merge sort on N inputs (N a power of two), in the order
/// they apply: applying each as "the lesser to lo, the greater to hi" sorts any N values ascending.
template <std::size_t N, class F>
constexpr void for_each_odd_even_merge_comparator(F&& f) {
  for (std::size_t p = 1; p < N; p <<= 1)
    for (std::size_t k = p; k >= 1; k >>= 1)
      for (std::size_t j = k % p; j + k < N; j += 2 * k)
        for (std::size_t i = 0; i < k && i + j + k < N; ++i)
          if ((i + j) / (2 * p) == (i + j + k) / (2 * p)) f(i + j, i + j + k);
}

template <std::size_t N>
constexpr std::size_t odd_even_merge_comparators() {
  std::size_t count = 0;
  for_each_odd_even_merge_comparator<N>([&count](std::size_t, std::size_t) { ++count; });
  return count;
}

/// The network as an array. It is fixed by N, so the compiler unrolls it into min and max instructions with no
/// branch on the data, where std::nth_element on a handful of values is mostly mispredicted branches.
template <std::size_t N>
constexpr std::array<Comparator, odd_even_merge_comparators<N>()> odd_even_merge_network() {
  static_assert(N >= 2 && (N & (N - 1)) == 0, "odd_even_merge_network: N must be a power of two");
  std::array<Comparator, odd_even_merge_comparators<N>()> net{};
  std::size_t n = 0;
  for_each_odd_even_merge_comparator<N>([&](std::size_t lo, std::size_t hi) { net[n++] = Comparator{lo, hi}; });
  return net;
}

/// The lesser and the greater of two numbers that are not NaN (std::min's and std::max's values), with no branch:
/// GCC compiles std::min on doubles, or the conditional expression, into a branch, which data such as depths
/// mispredict about half the time; minsd and maxsd decide in the register.
inline double lesser(double a, double b) {
#ifdef __SSE2__
  return _mm_cvtsd_f64(_mm_min_sd(_mm_set_sd(a), _mm_set_sd(b)));
#else
  return b < a ? b : a;
#endif
}

inline double greater(double a, double b) {
#ifdef __SSE2__
  return _mm_cvtsd_f64(_mm_max_sd(_mm_set_sd(a), _mm_set_sd(b)));
#else
  return a < b ? b : a;
#endif
}

template <std::size_t N, std::size_t... C>
inline void apply_network(std::array<double, N>& a, std::index_sequence<C...>) {
  constexpr auto net = odd_even_merge_network<N>();
  const auto exchange = [&a](std::size_t i, std::size_t j) {
    const double lo = lesser(a[i], a[j]), hi = greater(a[i], a[j]);
    a[i] = lo;
    a[j] = hi;
  };
  (exchange(net[C].lo, net[C].hi), ...);
}

/// Sorts N values (N a power of two; no NaN) ascending with Batcher's odd-even merge network: the same values in
/// the same order as std::sort.
template <std::size_t N>
inline void network_sort(std::array<double, N>& a) {
  apply_network(a, std::make_index_sequence<odd_even_merge_comparators<N>()>{});
}

}  // namespace graspmix::detail
