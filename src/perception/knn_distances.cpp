#include "knn_distances.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include <pcl/search/kdtree.h>

#include "flann_distance.hpp"

namespace graspmix::detail {

namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;

/// PCL's mean of the k nearest others from the k + 1 nearest squared distances in increasing order (the point
/// itself first): their square roots (in float) summed in double.
float mean_of_nearest(const float* ascending, int k) {
  double sum = 0.0;
  for (int j = 1; j < k + 1; ++j) sum += std::sqrt(ascending[j]);
  return static_cast<float>(sum / k);
}

/// A query looks at most this many candidates per neighbour it wants (else the kd-tree answers it).
constexpr std::size_t kMaxCandidatesPerNeighbour = 32;

/// The distance from a few points spread through the cloud to their (k1)-th nearest (themselves included), by
/// brute force; the median of them. What a grid cell should be about the size of.
double typical_reach(const Cloud& c, int k1) {
  constexpr std::size_t kSamples = 8;
  const std::size_t n = c.size();
  std::vector<float> d2(n);
  std::array<float, kSamples> reach{};
  for (std::size_t s = 0; s < kSamples; ++s) {
    const auto& p = c[s * n / kSamples];
    for (std::size_t j = 0; j < n; ++j) d2[j] = flann_squared(p, c[j].x, c[j].y, c[j].z);
    std::nth_element(d2.begin(), d2.begin() + (k1 - 1), d2.end());
    reach[s] = d2[static_cast<std::size_t>(k1 - 1)];
  }
  std::nth_element(reach.begin(), reach.begin() + kSamples / 2, reach.end());
  return std::sqrt(static_cast<double>(reach[kSamples / 2]));
}

/// The cloud's points sorted into cubic cells (x fastest), with a table of each cell's first slot.
struct CellGrid {
  double lo[3] = {0, 0, 0};
  double h = 0;
  std::int64_t dims[3] = {0, 0, 0};
  std::vector<int> start;                 ///< per cell (linear index) its first slot; one past the last at the end
  std::vector<int> row;                   ///< per slot its point's row in the cloud
  std::vector<float> x, y, z;             ///< per slot its point
  std::vector<std::int64_t> cell_of_row;  ///< per row its cell's linear index

  std::int64_t linear(std::int64_t i, std::int64_t j, std::int64_t k) const { return (k * dims[1] + j) * dims[0] + i; }
};

/// False when the cloud would need more than max_cells cells of side h.
bool make_grid(const Cloud& c, double h, double max_cells, CellGrid& g) {
  const auto n = static_cast<std::int64_t>(c.size());
  double hi[3];
  for (int a = 0; a < 3; ++a) g.lo[a] = std::numeric_limits<double>::infinity(), hi[a] = -g.lo[a];
  for (const auto& p : c) {
    const double q[3] = {p.x, p.y, p.z};
    for (int a = 0; a < 3; ++a) g.lo[a] = std::min(g.lo[a], q[a]), hi[a] = std::max(hi[a], q[a]);
  }
  double cells = 1;
  for (int a = 0; a < 3; ++a) {
    const double d = std::floor((hi[a] - g.lo[a]) / h) + 1;
    cells *= d;
    if (!(cells <= max_cells)) return false;
    g.dims[a] = static_cast<std::int64_t>(d);
  }
  g.h = h;
  g.cell_of_row.resize(static_cast<std::size_t>(n));
  g.start.assign(static_cast<std::size_t>(cells) + 1, 0);
  for (std::int64_t r = 0; r < n; ++r) {
    const auto& p = c[static_cast<std::size_t>(r)];
    const double q[3] = {p.x, p.y, p.z};
    std::int64_t ix[3];
    for (int a = 0; a < 3; ++a)
      ix[a] = std::clamp(static_cast<std::int64_t>(std::floor((q[a] - g.lo[a]) / h)), std::int64_t{0}, g.dims[a] - 1);
    const std::int64_t cell = g.linear(ix[0], ix[1], ix[2]);
    g.cell_of_row[static_cast<std::size_t>(r)] = cell;
    ++g.start[static_cast<std::size_t>(cell) + 1];
  }
  for (std::size_t i = 1; i < g.start.size(); ++i) g.start[i] += g.start[i - 1];
  g.row.resize(static_cast<std::size_t>(n));
  g.x.resize(static_cast<std::size_t>(n)), g.y.resize(static_cast<std::size_t>(n)),
      g.z.resize(static_cast<std::size_t>(n));
  // Each point at its cell's next free slot, the cell's start as the cursor (it ends at the next cell's start:
  // the table is shifted back after).
  for (std::int64_t r = 0; r < n; ++r) {
    const auto s =
        static_cast<std::size_t>(g.start[static_cast<std::size_t>(g.cell_of_row[static_cast<std::size_t>(r)])]++);
    const auto& p = c[static_cast<std::size_t>(r)];
    g.row[s] = static_cast<int>(r);
    g.x[s] = p.x, g.y[s] = p.y, g.z[s] = p.z;
  }
  for (std::size_t i = g.start.size() - 1; i > 0; --i) g.start[i] = g.start[i - 1];
  g.start[0] = 0;
  return true;
}

/// Point r's k1 nearest squared distances in increasing order into buf's front, from the 27 cells around its own;
/// false when something outside them could be nearer than the k1-th.
bool nearest_in_grid(const Cloud& c, const CellGrid& g, std::int64_t r, int k1, std::vector<float>& buf) {
  const auto& p = c[static_cast<std::size_t>(r)];
  const std::int64_t cell = g.cell_of_row[static_cast<std::size_t>(r)];
  const std::int64_t ix[3] = {cell % g.dims[0], (cell / g.dims[0]) % g.dims[1], cell / (g.dims[0] * g.dims[1])};
  // The nearest a point outside the 27 cells can be: the distance to the nearest face of the block that has cells
  // beyond it (past the grid's own edge there are no points). Only what is nearer than that is kept (with 2% of
  // margin on the squares for the rounding of the float distances and of the faces): if k1 are, they are the k1
  // nearest of the whole cloud.
  const double q[3] = {p.x, p.y, p.z};
  double reach = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (ix[a] - 1 > 0) reach = std::min(reach, q[a] - (g.lo[a] + g.h * static_cast<double>(ix[a] - 1)));
    if (ix[a] + 2 < g.dims[a]) reach = std::min(reach, g.lo[a] + g.h * static_cast<double>(ix[a] + 2) - q[a]);
  }
  const double bound = 0.98 * reach * reach;
  const std::int64_t x0 = std::max<std::int64_t>(ix[0] - 1, 0), x1 = std::min(ix[0] + 1, g.dims[0] - 1);
  const std::int64_t j0 = std::max<std::int64_t>(ix[1] - 1, 0), j1 = std::min(ix[1] + 1, g.dims[1] - 1);
  const std::int64_t z0 = std::max<std::int64_t>(ix[2] - 1, 0), z1 = std::min(ix[2] + 1, g.dims[2] - 1);
  // The block's slots: the cells x0..x1 of each row (j, k) are contiguous.
  std::array<std::pair<std::size_t, std::size_t>, 9> runs{};
  std::size_t n_runs = 0, total = 0;
  for (std::int64_t k = z0; k <= z1; ++k)
    for (std::int64_t j = j0; j <= j1; ++j) {
      const auto a = static_cast<std::size_t>(g.start[static_cast<std::size_t>(g.linear(x0, j, k))]);
      const auto b = static_cast<std::size_t>(g.start[static_cast<std::size_t>(g.linear(x1, j, k)) + 1]);
      runs[n_runs++] = {a, b};
      total += b - a;
    }
  // A block crowded far beyond k1 (a dense spot in cells sized for the cloud's typical reach) goes to the kd-tree:
  // every query there would measure against all of it.
  if (total > kMaxCandidatesPerNeighbour * static_cast<std::size_t>(k1)) return false;
  if (buf.size() < total) buf.resize(2 * total);
  // every candidate's distance first (a loop the compiler vectorises), then the near ones kept
  const float *xs = g.x.data(), *ys = g.y.data(), *zs = g.z.data();
  std::size_t n = 0;
  for (std::size_t t = 0; t < n_runs; ++t) {
    const auto [a, b] = runs[t];
    float* out = buf.data() + n;
    for (std::size_t s = a; s < b; ++s) out[s - a] = flann_squared(p, xs[s], ys[s], zs[s]);
    n += b - a;
  }
  const auto limit = static_cast<float>(bound);  // float(bound) <= bound * (1 + 2^-24): still inside the margin
  std::size_t m = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const float d2 = buf[i];
    buf[m] = d2;
    m += d2 < limit ? 1 : 0;
  }
  if (m < static_cast<std::size_t>(k1)) return false;
  std::nth_element(buf.begin(), buf.begin() + (k1 - 1), buf.begin() + static_cast<std::ptrdiff_t>(m));
  std::sort(buf.begin(), buf.begin() + (k1 - 1));  // the k1-th is in place: the k1 - 1 before it, in order
  return true;
}

/// The statistic from PCL's kd-tree (its own search, as pcl::StatisticalOutlierRemoval builds it) for `rows`.
void kd_tree_means(const Cloud::ConstPtr& cloud, int k, const std::vector<std::int64_t>& rows, KnnDistances& out) {
  pcl::search::KdTree<pcl::PointXYZ> tree(false);
  tree.setInputCloud(cloud);
  const auto n = static_cast<std::int64_t>(rows.size());
  int valid = 0;
#pragma omp parallel reduction(+ : valid)
  {
    pcl::Indices nn(static_cast<std::size_t>(k) + 1);
    std::vector<float> d2(static_cast<std::size_t>(k) + 1);
#pragma omp for schedule(static)
    for (std::int64_t t = 0; t < n; ++t) {
      const auto i = static_cast<std::size_t>(rows[static_cast<std::size_t>(t)]);
      const auto& p = (*cloud)[i];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
      if (tree.nearestKSearch(static_cast<pcl::index_t>(i), k + 1, nn, d2) == 0) continue;
      out.mean[i] = mean_of_nearest(d2.data(), k);  // FLANN's results come nearest first
      ++valid;
    }
  }
  out.valid += valid;
}

}  // namespace

KnnDistances knn_mean_distances(const Cloud::ConstPtr& cloud, int k) {
  const auto n = static_cast<std::int64_t>(cloud->size());
  const int k1 = k + 1;
  KnnDistances out;
  out.mean.assign(static_cast<std::size_t>(n), 0.0f);
  std::vector<std::int64_t> rest;
  const bool finite = std::all_of(cloud->begin(), cloud->end(), [](const pcl::PointXYZ& p) {
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
  });
  CellGrid grid;
  const double reach = finite && n > k1 ? typical_reach(*cloud, k1) : 0.0;
  // Cells of one and a half reaches (most points' k1 nearest lie inside their 27), or wider where the cloud's box
  // would need more than 16 cells a point (a far stray point): at most 64 bytes of table a point.
  const double max_cells = 16.0 * static_cast<double>(n) + 1e5;
  bool gridded = false;
  if (reach > 0) {
    double h = 1.5 * reach;
    for (int tries = 0; tries < 8 && !gridded; ++tries, h *= 2.0) gridded = make_grid(*cloud, h, max_cells, grid);
  }
  if (gridded) {
    std::vector<char> found(static_cast<std::size_t>(n), 0);
#pragma omp parallel
    {
      std::vector<float> buf;
#pragma omp for schedule(static)
      for (std::int64_t s = 0; s < n; ++s) {  // in the grid's order: neighbouring queries read the same cells
        const std::int64_t r = grid.row[static_cast<std::size_t>(s)];
        if (!nearest_in_grid(*cloud, grid, r, k1, buf)) continue;
        out.mean[static_cast<std::size_t>(r)] = mean_of_nearest(buf.data(), k);
        found[static_cast<std::size_t>(r)] = 1;
      }
    }
    for (std::int64_t r = 0; r < n; ++r) {
      if (found[static_cast<std::size_t>(r)])
        ++out.valid;
      else
        rest.push_back(r);
    }
  } else {
    rest.resize(static_cast<std::size_t>(n));
    for (std::int64_t r = 0; r < n; ++r) rest[static_cast<std::size_t>(r)] = r;
  }
  out.from_tree = static_cast<int>(rest.size());
  if (!rest.empty()) kd_tree_means(cloud, k, rest, out);
  return out;
}

}  // namespace graspmix::detail
