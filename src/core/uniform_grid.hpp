#pragma once
// A uniform grid over a point cloud, private to the library: the surface features' radius search
// (perception/surface.cpp) and the collision expert's box search (grasp/collision.cpp) share it.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <tuple>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "graspmix/core/types.hpp"

namespace graspmix::detail {

/// Points bucketed into cubic cells of side `cell_size` from `origin`: p lies in the cell
/// floor((p - origin) / cell_size), clamped to [0, dims - 1] on every axis.
///
/// The points are kept in one canonical order: by cell (x, then y, then z), then by coordinates, then by
/// input row. Every query visits points in that order, so results that sum over neighbours do not depend
/// on the order of the input; and the points of one cell, and of a run of cells along z, are contiguous.
///
/// A cell's points are found through a table over all cells (Layout::Dense, O(1), for grids with a bounded
/// number of cells) or a hash of the occupied cells (Layout::Sparse, for grids too large for a table).
class UniformGrid {
 public:
  using Cell = std::array<std::int64_t, 3>;
  enum class Layout { Dense, Sparse };
  /// The sparse layout packs a cell into 21 bits per axis: dims may not exceed this.
  static constexpr std::int64_t kMaxCells = std::int64_t{1} << 21;

  UniformGrid(const Eigen::Ref<const Vec3Array>& P, const Eigen::Vector3d& origin, double cell_size, const Cell& dims,
              Layout layout)
      : origin_(origin), h_(cell_size), dims_(dims), layout_(layout) {
    if (!(cell_size > 0)) throw std::invalid_argument("UniformGrid: the cell size must be positive");
    for (const std::int64_t d : dims) {
      if (d < 1 || (layout == Layout::Sparse && d > kMaxCells)) throw std::invalid_argument("UniformGrid: bad dims");
    }
    if (layout == Layout::Dense &&
        static_cast<double>(dims[0]) * static_cast<double>(dims[1]) * static_cast<double>(dims[2]) > 1e9) {
      throw std::invalid_argument("UniformGrid: too many cells for a dense table");
    }
    const Eigen::Index N = P.rows();
    std::vector<Cell> cell(static_cast<std::size_t>(N));
    // The canonical order sorted on copies: the cell as its linear index (x, then y, then z: the same order, as
    // every index lies inside dims; at most 63 bits), then the coordinates, then the row, all in one record.
    struct Entry {
      std::int64_t cell;
      double x, y, z;
      Eigen::Index row;
    };
    std::vector<Entry> entries(static_cast<std::size_t>(N));
    for (Eigen::Index i = 0; i < N; ++i) {
      const auto k = static_cast<std::size_t>(i);
      cell[k] = cell_of(P.row(i).transpose());
      entries[k] = {linear(cell[k]), P(i, 0), P(i, 1), P(i, 2), i};
    }
    std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
      if (a.cell != b.cell) return a.cell < b.cell;
      return std::make_tuple(a.x, a.y, a.z, a.row) < std::make_tuple(b.x, b.y, b.z, b.row);
    });
    order_.resize(static_cast<std::size_t>(N));
    p_.resize(static_cast<std::size_t>(N));
    cells_.resize(static_cast<std::size_t>(N));
    for (std::size_t s = 0; s < entries.size(); ++s) {
      order_[s] = entries[s].row;
      p_[s] = Eigen::Vector3d(entries[s].x, entries[s].y, entries[s].z);
      cells_[s] = cell[static_cast<std::size_t>(entries[s].row)];
    }
    if (layout == Layout::Dense) {
      start_.assign(static_cast<std::size_t>(dims[0] * dims[1] * dims[2] + 1), 0);
      for (const Cell& c : cells_) ++start_[static_cast<std::size_t>(linear(c) + 1)];
      for (std::size_t k = 1; k < start_.size(); ++k) start_[k] += start_[k - 1];
    } else {
      ranges_.reserve(static_cast<std::size_t>(N));
      for (std::size_t s = 0; s < cells_.size(); ++s) {
        const auto it = ranges_.find(pack(cells_[s]));
        if (it == ranges_.end())
          ranges_.emplace(pack(cells_[s]),
                          std::make_pair(static_cast<Eigen::Index>(s), static_cast<Eigen::Index>(s) + 1));
        else
          it->second.second = static_cast<Eigen::Index>(s) + 1;
      }
    }
  }

  /// A grid of cells `cell_size` wide over the bounds of P (not empty, finite) widened by `pad` on every side: dense
  /// below a million cells, sparse above; the cell counts clamped as doubles to kMaxCells before the cast.
  static UniformGrid covering(const Eigen::Ref<const Vec3Array>& P, double cell_size, double pad = 0.0) {
    if (P.rows() == 0 || !P.allFinite()) throw std::invalid_argument("UniformGrid: no points, or points not finite");
    const Eigen::Vector3d lo = P.colwise().minCoeff().transpose().array() - pad;
    const Eigen::Vector3d hi = P.colwise().maxCoeff().transpose();
    Cell dims{};
    double cells = 1;
    for (std::size_t k = 0; k < 3; ++k) {
      const auto e = static_cast<Eigen::Index>(k);
      const double n = std::floor((hi[e] - lo[e] + pad) / cell_size) + 1;
      dims[k] = static_cast<std::int64_t>(std::min(n, static_cast<double>(kMaxCells)));
      cells *= static_cast<double>(dims[k]);
    }
    return UniformGrid(P, lo, cell_size, dims, cells < 1e6 ? Layout::Dense : Layout::Sparse);
  }

  int size() const { return static_cast<int>(p_.size()); }
  double cell_size() const { return h_; }
  const Cell& dims() const { return dims_; }
  /// canonical position -> input row
  Eigen::Index row(int i) const { return order_[static_cast<std::size_t>(i)]; }
  /// The point at a canonical position, and its cell.
  const Eigen::Vector3d& point(int i) const { return p_[static_cast<std::size_t>(i)]; }
  const Cell& cell(int i) const { return cells_[static_cast<std::size_t>(i)]; }

  /// The cell of a point (clamped into the grid).
  Cell cell_of(const Eigen::Vector3d& p) const {
    Cell c;
    for (int k = 0; k < 3; ++k) {
      const auto v = static_cast<std::int64_t>(std::floor((p[k] - origin_[k]) / h_));
      c[static_cast<std::size_t>(k)] = std::clamp<std::int64_t>(v, 0, dims_[static_cast<std::size_t>(k)] - 1);
    }
    return c;
  }

  /// Canonical positions [first, second) of the points in the cells (x, y, z0..z1) of the grid.
  std::pair<Eigen::Index, Eigen::Index> z_run(std::int64_t x, std::int64_t y, std::int64_t z0, std::int64_t z1) const {
    if (layout_ == Layout::Dense) {
      return {start_[static_cast<std::size_t>(linear({x, y, z0}))],
              start_[static_cast<std::size_t>(linear({x, y, z1}) + 1)]};
    }
    std::pair<Eigen::Index, Eigen::Index> run{0, 0};
    bool any = false;
    for (std::int64_t z = z0; z <= z1; ++z) {
      const auto it = ranges_.find(pack({x, y, z}));
      if (it == ranges_.end()) continue;
      if (!any) run.first = it->second.first;
      run.second = it->second.second;
      any = true;
    }
    return run;
  }

  /// Calls f(i) for the canonical position i of every point in the cells c0..c1 (inclusive, inside the
  /// grid), in canonical order.
  template <class F>
  void for_each_in_cells(const Cell& c0, const Cell& c1, F&& f) const {
    for (std::int64_t x = c0[0]; x <= c1[0]; ++x)
      for (std::int64_t y = c0[1]; y <= c1[1]; ++y) {
        const auto [b, e] = z_run(x, y, c0[2], c1[2]);
        for (Eigen::Index i = b; i < e; ++i) f(static_cast<int>(i));
      }
  }

  /// Every j (i itself included) with |p_j - p_i|^2 <= r2, in canonical order, with that squared
  /// distance. Complete when r2 <= cell_size^2: it visits the 27 cells around i's.
  void neighbours(int i, double r2, std::vector<int>& nn, std::vector<double>& d2) const {
    nn.clear();
    d2.clear();
    const Cell& c = cell(i);
    const Eigen::Vector3d& p = point(i);
    for (std::int64_t x = c[0] - 1; x <= c[0] + 1; ++x) {
      if (x < 0 || x >= dims_[0]) continue;
      for (std::int64_t y = c[1] - 1; y <= c[1] + 1; ++y) {
        if (y < 0 || y >= dims_[1]) continue;
        const auto [b, e] = z_run(x, y, std::max<std::int64_t>(c[2] - 1, 0), std::min(c[2] + 1, dims_[2] - 1));
        for (Eigen::Index j = b; j < e; ++j) {
          const double d = (p_[static_cast<std::size_t>(j)] - p).squaredNorm();
          if (d <= r2) {
            nn.push_back(static_cast<int>(j));
            d2.push_back(d);
          }
        }
      }
    }
  }

 private:
  std::int64_t linear(const Cell& c) const { return (c[0] * dims_[1] + c[1]) * dims_[2] + c[2]; }
  static std::uint64_t pack(const Cell& c) {
    return (static_cast<std::uint64_t>(c[0]) << 42) | (static_cast<std::uint64_t>(c[1]) << 21) |
           static_cast<std::uint64_t>(c[2]);
  }

  Eigen::Vector3d origin_;
  double h_;
  Cell dims_;
  Layout layout_;
  std::vector<Eigen::Index> order_;
  std::vector<Eigen::Vector3d> p_;
  std::vector<Cell> cells_;
  std::vector<Eigen::Index> start_;                                                  ///< Dense: size cells + 1
  std::unordered_map<std::uint64_t, std::pair<Eigen::Index, Eigen::Index>> ranges_;  ///< Sparse
};

}  // namespace graspmix::detail
