// The library's private sorting network against Knuth's comparator count, the 0-1 principle and std::sort.
#include <algorithm>
#include <array>
#include <cstdint>
#include <random>

#include <gtest/gtest.h>

#include "core/sorting_network.hpp"

using graspmix::detail::network_sort;
using graspmix::detail::odd_even_merge_comparators;

namespace {

template <std::size_t N>
void expect_sorts_like_std_sort(std::uint64_t seed, int trials) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.2, 2.0);
  std::uniform_int_distribution<int> few(0, 3);
  for (int t = 0; t < trials; ++t) {
    std::array<double, N> a{};
    // half the trials draw from four values: ties, as neighbouring pixels of a flat surface give
    for (double& x : a) x = t % 2 ? u(rng) : 0.5 + 0.001 * few(rng);
    std::array<double, N> expected = a;
    std::sort(expected.begin(), expected.end());
    network_sort(a);
    ASSERT_EQ(a, expected) << "N = " << N << ", trial " << t;
  }
}

}  // namespace

TEST(SortingNetwork, HasBatchersNumberOfComparators) {
  // Knuth, TAOCP 5.3.4: Batcher's merge exchange sorts 2^t values with (t^2 - t + 4) 2^(t-2) - 1 comparators.
  EXPECT_EQ(odd_even_merge_comparators<2>(), 1u);
  EXPECT_EQ(odd_even_merge_comparators<4>(), 5u);
  EXPECT_EQ(odd_even_merge_comparators<8>(), 19u);
  EXPECT_EQ(odd_even_merge_comparators<16>(), 63u);
  EXPECT_EQ(odd_even_merge_comparators<32>(), 191u);
}

TEST(SortingNetwork, SortsEveryZeroOneInputOfSixteen) {
  // The 0-1 principle: a comparator network that sorts every input of zeros and ones sorts every input.
  for (std::uint32_t bits = 0; bits < (1u << 16); ++bits) {
    std::array<double, 16> a{};
    int ones = 0;
    for (int i = 0; i < 16; ++i) ones += (a[static_cast<std::size_t>(i)] = (bits >> i) & 1u ? 1.0 : 0.0) > 0 ? 1 : 0;
    network_sort(a);
    for (int i = 0; i < 16; ++i) ASSERT_EQ(a[static_cast<std::size_t>(i)], i >= 16 - ones ? 1.0 : 0.0) << bits;
  }
}

TEST(SortingNetwork, GivesStdSortsOrder) {
  expect_sorts_like_std_sort<2>(1, 200);
  expect_sorts_like_std_sort<4>(2, 200);
  expect_sorts_like_std_sort<8>(3, 200);
  expect_sorts_like_std_sort<16>(4, 2000);
  expect_sorts_like_std_sort<32>(5, 200);
}
