#include "graspmix/perception/depth_scene.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#ifdef __SSE2__
#include <emmintrin.h>
#endif

#include "core/parallel_rows.hpp"
#include "core/sorting_network.hpp"
#include "graspmix/perception/cleanup.hpp"
#include "graspmix/perception/visibility.hpp"
#include "segmentation_steps.hpp"
#include "table_noise.hpp"

namespace graspmix {

namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

/// One point per block of stride x stride pixels of an organized sensor-frame cloud S (row v * width + u, NaN
/// rows = no return): the mean of the block's returns within `near` of their median depth (one surface: not a
/// blend across an occluding edge, and not biased towards the camera as the nearest return would be under depth
/// noise), in the world frame, with the pixel index of the first of them.
struct Blocks {
  Vec3Array points;
  Eigen::VectorXi pixels;
};

/// Which blocks block_points keeps: those whose point lies more than `height` above `plane` (world frame), or all
/// without a plane; `seen` counts every block with a return, kept or not.
struct BlockFilter {
  const SegmentationSettings& settings;  ///< its workspace: blocks outside are neither kept nor seen
  const Eigen::Vector4d* plane = nullptr;
  double height = 0;
  Eigen::Index seen = 0;
};

/// The upper middle of z's values (z reordered): a block of 4 x 4 returns, the coarse blocks' usual case, through a
/// sorting network, the same value as std::nth_element's in a fraction of its time.
double upper_median(std::vector<double>& z) {
  if (z.size() == 16) {
    std::array<double, 16> a;
    std::copy(z.begin(), z.end(), a.begin());
    detail::network_sort(a);
    return a[8];
  }
  const auto mid = z.begin() + static_cast<std::ptrdiff_t>(z.size() / 2);
  std::nth_element(z.begin(), mid, z.end());
  return *mid;
}

/// One row of blocks' kept points (world frame, x, y, z in turn) with their pixels, and how many of its blocks were
/// seen: block_points makes its rows on threads of their own and joins them in order.
struct BlockRow {
  std::vector<double> xyz;
  std::vector<int> pixels;
  Eigen::Index seen = 0;
};

/// A thread's buffers for a block's returns and their depths.
struct BlockBuffers {
  std::vector<std::pair<int, int>> returns;  ///< (v, u)
  std::vector<double> z;
};

/// The sensor-frame points of an organized cloud, pixel by pixel: (v, u) is row v * width + u of S, a return where
/// the row is finite.
struct OrganizedPixels {
  const Eigen::Ref<const Vec3Array>& S;
  int width;
  bool has(int v, int u) const { return S.row(index(v, u)).allFinite(); }
  double z(int v, int u) const { return S(index(v, u), 2); }
  Eigen::Vector3d point(int v, int u) const { return S.row(index(v, u)).transpose(); }
  Eigen::Index index(int v, int u) const { return static_cast<Eigen::Index>(v) * width + u; }
};

/// The same of a depth image, each point back-projected where it is read (PinholeCamera::back_project's values,
/// without the image of points it would make).
struct DepthPixels {
  const Eigen::Ref<const DepthImage>& depth;
  const PinholeCamera& camera;
  bool has(int v, int u) const { return has_return(depth(v, u)); }
  double z(int v, int u) const { return depth(v, u); }
  Eigen::Vector3d point(int v, int u) const { return camera.back_project(u, v, depth(v, u)); }
};

template <class Pixels>
Blocks block_points(const Pixels& S, int height, int width, int stride, double near, const Eigen::Isometry3d& T,
                    BlockFilter& filter, int every = 1) {
  // A block's height above the plane from its sensor-frame point: n . (T p) + d = (R^T n) . p + (n . t + d).
  Eigen::Vector3d n_sensor = Eigen::Vector3d::Zero();
  double d_sensor = 1;  // without a plane every block is "above"
  if (filter.plane != nullptr) {
    n_sensor = T.linear().transpose() * filter.plane->head<3>();
    d_sensor = filter.plane->head<3>().dot(T.translation()) + (*filter.plane)[3] - filter.height;
  }
  const bool crop = !filter.settings.workspace.empty();
  // Whether the block of sensor-frame point p is kept, its world point in `world`: inside the workspace (counted
  // in `seen`) and above the plane.
  const auto keep = [&](const Eigen::Vector3d& p, Eigen::Vector3d& world, Eigen::Index& seen) {
    if (crop && !detail::in_workspace(filter.settings, world = T * p)) return false;
    ++seen;
    if (!(n_sensor.dot(p) + d_sensor > 0)) return false;
    if (!crop) world = T * p;
    return true;
  };
  const int rows = (height + stride - 1) / stride, cols = (width + stride - 1) / stride;
  std::vector<BlockRow> made(static_cast<std::size_t>(rows));
  detail::parallel_rows<BlockBuffers>(rows, [&](BlockBuffers& buffers, std::int64_t i) {
    const int bv = static_cast<int>(i);  // row bv of blocks into made[bv]
    if (bv % every != 0) return;         // one block in `every` along each axis
    BlockRow& row = made[static_cast<std::size_t>(bv)];
    std::vector<std::pair<int, int>>& returns = buffers.returns;
    std::vector<double>& z = buffers.z;
    Eigen::Vector3d world;
    const auto add = [&row, &world, width](int v, int u) {
      row.xyz.insert(row.xyz.end(), world.data(), world.data() + 3);
      row.pixels.push_back(v * width + u);
    };
    for (int bu = 0; bu < cols; bu += every) {
      if (stride == 1) {  // each return its own block
        if (S.has(bv, bu) && keep(S.point(bv, bu), world, row.seen)) add(bv, bu);
        continue;
      }
      returns.clear();
      z.clear();
      for (int v = bv * stride; v < std::min(height, (bv + 1) * stride); ++v)
        for (int u = bu * stride; u < std::min(width, (bu + 1) * stride); ++u) {
          if (!S.has(v, u)) continue;
          returns.emplace_back(v, u);
          z.push_back(S.z(v, u));
        }
      if (returns.empty()) continue;
      const double median = upper_median(z);
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      int count = 0;
      std::pair<int, int> first{-1, -1};
      for (const auto& [v, u] : returns) {
        if (std::abs(S.z(v, u) - median) > near) continue;
        sum += S.point(v, u);
        if (count++ == 0) first = {v, u};
      }
      // the median's own return is always counted
      if (keep(sum / count, world, row.seen)) add(first.first, first.second);
    }
  });
  Eigen::Index n = 0;
  for (const BlockRow& row : made) n += static_cast<Eigen::Index>(row.pixels.size());
  Blocks b{Vec3Array(n, 3), Eigen::VectorXi(n)};
  n = 0;
  for (const BlockRow& row : made) {
    for (std::size_t i = 0; i < row.pixels.size(); ++i, ++n) {
      b.points.row(n) << row.xyz[3 * i], row.xyz[3 * i + 1], row.xyz[3 * i + 2];
      b.pixels[n] = row.pixels[i];
    }
    filter.seen += row.seen;
  }
  return b;
}

/// The depth image the join rule judges gaps on: each pixel the nearest return within the k x k pixels around it
/// (k: visibility_resolution's angle in pixels, odd), as a bin of segment_scene's spherical range images holds its
/// nearest point. Separable: the nearest along rows, then along columns.
DepthImage nearest_pool(const Eigen::Ref<const DepthImage>& depth, const PinholeCamera& camera, double resolution) {
  const int half = static_cast<int>(std::lround(resolution * std::min(camera.fx(), camera.fy()))) / 2;
  const double inf = std::numeric_limits<double>::infinity();
  DepthImage out = depth.unaryExpr([inf](double d) { return has_return(d) ? d : inf; });
  if (half == 0) return out;
  const Eigen::Index H = depth.rows(), W = depth.cols();
  DepthImage rows(H, W);
  for (Eigen::Index v = 0; v < H; ++v)
    for (Eigen::Index u = 0; u < W; ++u)
      rows(v, u) = out.row(v)
                       .segment(std::max<Eigen::Index>(0, u - half),
                                std::min(W - 1, u + half) - std::max<Eigen::Index>(0, u - half) + 1)
                       .minCoeff();
  for (Eigen::Index v = 0; v < H; ++v) {
    const Eigen::Index lo = std::max<Eigen::Index>(0, v - half), n = std::min(H - 1, v + half) - lo + 1;
    out.row(v) = rows.middleRows(lo, n).colwise().minCoeff();
  }
  return out;
}

/// The median of a window of returns, general: any radius, returns missing.
double window_median(const Eigen::Ref<const DepthImage>& depth, Eigen::Index v, Eigen::Index u, int r,
                     std::vector<double>& window) {
  const Eigen::Index H = depth.rows(), W = depth.cols();
  window.clear();
  for (Eigen::Index y = std::max<Eigen::Index>(0, v - r); y <= std::min(H - 1, v + r); ++y)
    for (Eigen::Index x = std::max<Eigen::Index>(0, u - r); x <= std::min(W - 1, u + r); ++x)
      if (has_return(depth(y, x))) window.push_back(depth(y, x));
  return upper_median(window);
}

/// The middle of three values.
double median3(double a, double b, double c) { return std::max(std::min(a, b), std::min(std::max(a, b), c)); }

/// The median of nine for every pixel u in [1, W - 1) of row v (1 <= v < H - 1) into med[u], and whether its 3 x 3
/// window is all returns into full[u] (only those medians are used). Each column of three is sorted once (its
/// least, middle, greatest); the median of nine is the middle of (the greatest least, the middle middle, the least
/// greatest) of three neighbouring columns: the same value as any exact median. Two pixels at a time with SSE2
/// (minpd and maxpd, exact on numbers), else one.
void row_medians_of_nine(const Eigen::Ref<const DepthImage>& depth, Eigen::Index v, std::vector<double>& lo,
                         std::vector<double>& mid, std::vector<double>& hi, std::vector<char>& column_full,
                         std::vector<double>& med) {
  const Eigen::Index W = depth.cols();
  const double* a = &depth.coeffRef(v - 1, 0);
  const double* b = &depth.coeffRef(v, 0);
  const double* c = &depth.coeffRef(v + 1, 0);
  Eigen::Index u = 0;
#ifdef __SSE2__
  // median3 two lanes at a time
  const auto middle_of = [](__m128d x, __m128d y, __m128d z) {
    return _mm_max_pd(_mm_min_pd(x, y), _mm_min_pd(_mm_max_pd(x, y), z));
  };
  const __m128d zero = _mm_setzero_pd(), inf = _mm_set1_pd(std::numeric_limits<double>::infinity());
  const auto returns = [&](__m128d x) { return _mm_and_pd(_mm_cmpgt_pd(x, zero), _mm_cmplt_pd(x, inf)); };
  for (; u + 2 <= W; u += 2) {
    const __m128d x = _mm_loadu_pd(a + u), y = _mm_loadu_pd(b + u), z = _mm_loadu_pd(c + u);
    _mm_storeu_pd(&lo[static_cast<std::size_t>(u)], _mm_min_pd(_mm_min_pd(x, y), z));
    _mm_storeu_pd(&hi[static_cast<std::size_t>(u)], _mm_max_pd(_mm_max_pd(x, y), z));
    _mm_storeu_pd(&mid[static_cast<std::size_t>(u)], middle_of(x, y, z));
    const int m = _mm_movemask_pd(_mm_and_pd(_mm_and_pd(returns(x), returns(y)), returns(z)));
    column_full[static_cast<std::size_t>(u)] = static_cast<char>(m & 1);
    column_full[static_cast<std::size_t>(u) + 1] = static_cast<char>(m >> 1);
  }
#endif
  for (; u < W; ++u) {
    const auto k = static_cast<std::size_t>(u);
    column_full[k] = static_cast<char>(has_return(a[u]) && has_return(b[u]) && has_return(c[u]));
    lo[k] = std::min({a[u], b[u], c[u]});
    hi[k] = std::max({a[u], b[u], c[u]});
    mid[k] = median3(a[u], b[u], c[u]);
  }
  std::size_t k = 1;
  const auto end = static_cast<std::size_t>(W - 1);
#ifdef __SSE2__
  for (; k + 2 <= end; k += 2) {
    const auto at = [](const std::vector<double>& x, std::size_t i) { return _mm_loadu_pd(&x[i]); };
    const __m128d greatest_least = _mm_max_pd(_mm_max_pd(at(lo, k - 1), at(lo, k)), at(lo, k + 1));
    const __m128d least_greatest = _mm_min_pd(_mm_min_pd(at(hi, k - 1), at(hi, k)), at(hi, k + 1));
    const __m128d middle = middle_of(at(mid, k - 1), at(mid, k), at(mid, k + 1));
    _mm_storeu_pd(&med[k], middle_of(greatest_least, middle, least_greatest));
  }
#endif
  for (; k < end; ++k) {
    med[k] = median3(std::max({lo[k - 1], lo[k], lo[k + 1]}), median3(mid[k - 1], mid[k], mid[k + 1]),
                     std::min({hi[k - 1], hi[k], hi[k + 1]}));
  }
}

/// The depth image the scene's visibility model keeps: each pixel with a return the median of the returns within r
/// pixels of it (a (2r + 1)^2 window; r = 0: the image itself). A depth sensor's silhouettes are ragged (the
/// simulated cameras' lateral noise, a real one's flying pixels): an object's pixel at its outline that took the
/// depth of the table behind sees through the object, and its ray would refute every completion there; the median
/// removes such lone pixels and keeps edges where they are.
DepthImage median_filtered(const Eigen::Ref<const DepthImage>& depth, int r) {
  DepthImage out = depth;
  if (r == 0) return out;
  const Eigen::Index H = depth.rows(), W = depth.cols();
  struct Buffers {  // a thread's, made at its first row
    std::vector<double> window, lo, mid, hi, med;
    std::vector<char> full;
  };
  detail::parallel_rows<Buffers>(H, [&](Buffers& b, Eigen::Index v) {
    if (b.lo.empty()) {
      for (std::vector<double>* x : {&b.lo, &b.mid, &b.hi, &b.med}) x->resize(static_cast<std::size_t>(W));
      b.full.resize(static_cast<std::size_t>(W));
      b.window.reserve(static_cast<std::size_t>((2 * r + 1) * (2 * r + 1)));
    }
    // The usual case, r = 1 inside the image with nine returns, row by row (row_medians_of_nine); the others one
    // window at a time.
    const bool rows_inside = r == 1 && v > 0 && v + 1 < H;
    if (rows_inside) row_medians_of_nine(depth, v, b.lo, b.mid, b.hi, b.full, b.med);
    for (Eigen::Index u = 0; u < W; ++u) {
      if (!has_return(depth(v, u))) continue;
      const auto k = static_cast<std::size_t>(u);
      if (rows_inside && u > 0 && u + 1 < W && b.full[k - 1] && b.full[k] && b.full[k + 1]) {
        out(v, u) = b.med[k];
        continue;
      }
      out(v, u) = window_median(depth, v, u, r, b.window);
    }
  });
  return out;
}

/// The blocks' points through prepare_cloud's voxel grid, each with the pixel of the block it came from.
Blocks voxelised(const Blocks& b, double voxel_size) {
  if (b.points.rows() == 0) return b;  // nothing above the table: the scene's rule says so, not the voxel grid
  CleanupSettings voxel;               // prepare_cloud's voxel grid only: the sources follow every centroid
  voxel.voxel_size = voxel_size;
  voxel.remove_outliers = false;
  voxel.remove_plane = false;
  CleanupResult down;
  try {
    down = prepare_cloud(b.points, voxel);
  } catch (const std::invalid_argument& e) {  // a scene kilometres wide: most likely the image's units, not a scene
    throw std::invalid_argument(std::string(e.what()) +
                                "; from a depth image, check its depth scale (metres per unit: 0.001 for millimetres) "
                                "and the intrinsics (pixels)");
  }
  Blocks out{std::move(down.points), Eigen::VectorXi(down.sources.size())};
  for (Eigen::Index i = 0; i < out.pixels.size(); ++i) out.pixels[i] = b.pixels[down.sources[i]];
  return out;
}

/// The rows of b at most `height` above `plane` (or below it): the table.
Blocks on_plane(const Blocks& b, const Eigen::Vector4d& plane, double height) {
  const Eigen::VectorXd h = detail::heights(b.points, plane);
  const auto keep = [&](Eigen::Index i) { return !(h[i] > height); };
  Eigen::Index n = 0;
  for (Eigen::Index i = 0; i < h.size(); ++i) n += keep(i) ? 1 : 0;
  Blocks out{Vec3Array(n, 3), Eigen::VectorXi(n)};
  n = 0;
  for (Eigen::Index i = 0; i < h.size(); ++i)
    if (keep(i)) out.points.row(n) = b.points.row(i), out.pixels[n++] = b.pixels[i];
  return out;
}

/// Two voxelised sets as one (each voxelised on its own: no voxel mixes the two).
Blocks joined(const Blocks& a, const Blocks& b) {
  Blocks out{Vec3Array(a.points.rows() + b.points.rows(), 3), Eigen::VectorXi(a.pixels.size() + b.pixels.size())};
  out.points << a.points, b.points;
  out.pixels << a.pixels, b.pixels;
  return out;
}

/// segment_depth's steps on an organized sensor-frame cloud S (its pixels: OrganizedPixels or DepthPixels) and its
/// depth image. The support plane is searched for (or a given one turned towards the camera) on blocks of
/// plane_image_stride pixels: RANSAC and the rule need the table's extent, not its every point; the objects are then
/// made of the fine blocks above it.
template <class Pixels>
Segmentation segment_image(const Pixels& S, const Eigen::Ref<const DepthImage>& depth, const PinholeCamera& camera,
                           const Eigen::Isometry3d& T, const SegmentationSettings& s,
                           const std::optional<Eigen::Vector4d>& plane, Clock::time_point t0, std::int64_t n_returns) {
  Segmentation out;
  out.n_input = static_cast<std::size_t>(n_returns);
  detail::Cameras cams;
  cams.given = true;
  cams.single = T.translation();
  const int H = camera.height(), W = camera.width(), fine = image_stride(depth, camera, s);
  const bool two_levels = (plane || s.find_plane) && s.plane_image_stride > fine;
  auto t_step = Clock::now();
  Blocks down, sample;
  std::size_t dropped = 0, on_table = 0;
  if (two_levels) {
    // The objects from the fine blocks above the table, the table from the coarse ones on it (and behind it: the
    // rule that names a camera below the table counts them); each voxelised on its own, so no voxel blends an
    // object's foot with the table. The table's noise is measured on `sample`, below.
    BlockFilter all{s};
    const Blocks blocks = block_points(S, H, W, s.plane_image_stride, s.voxel_size, T, all);
    if (all.seen == 0) detail::nothing_in_workspace(s, "the image (a depth image or an organized cloud)");
    const Blocks coarse = voxelised(blocks, s.voxel_size);
    out.times.voxel += since(t_step);
    detail::search_support(coarse.points, cams, s, plane, out);
    t_step = Clock::now();
    if (out.plane_found || out.plane_given) {
      BlockFilter above{s, &out.plane, s.table_clearance};  // only the fine blocks above the table are made
      const Blocks up = block_points(S, H, W, fine, s.voxel_size, T, above);
      const Blocks on = on_plane(coarse, out.plane, s.table_clearance);
      down = joined(voxelised(up, s.voxel_size), on);
      // n_plane counts the fine blocks on the table, not the coarse ones that stand in for them
      dropped = static_cast<std::size_t>(above.seen - up.points.rows());
      on_table = static_cast<std::size_t>(on.points.rows());
      // The table's noise measured on fine blocks, one at every coarse block's place: the coarse blocks' medians
      // of more returns scatter less than the fine ones above the table, and the fine ones above it are all there
      // while the table's below it are not: the table's noise rule (segmentation.hpp) would find neither the
      // scatter nor the symmetry of the fine blocks' noise (a bare table with 3 mm of noise a pixel gave objects).
      BlockFilter every_place{s};
      sample = block_points(S, H, W, fine, s.voxel_size, T, every_place, std::max(1, s.plane_image_stride / fine));
    }
  }
  if (!out.plane_found && !out.plane_given) {
    BlockFilter all{s};
    const Blocks blocks = block_points(S, H, W, fine, s.voxel_size, T, all);
    if (all.seen == 0) detail::nothing_in_workspace(s, "the image (a depth image or an organized cloud)");
    down = voxelised(blocks, s.voxel_size);
  }
  out.n_after_voxel = static_cast<std::size_t>(down.points.rows());
  out.times.voxel += since(t_step);
  t_step = Clock::now();
  out.visibility = std::make_shared<const VisibilityModel>(VisibilityModel::from_depth(
      median_filtered(depth, s.visibility_median_window), camera, T, detail::visibility_settings(s)));
  out.times.visibility = since(t_step);
  // The join rule's pooled image, made only when it has pieces to judge (its time is the join step's).
  cams.join_model = [&]() {
    return std::make_shared<const VisibilityModel>(VisibilityModel::from_depth(
        nearest_pool(depth, camera, s.visibility_resolution), camera, T, detail::visibility_settings(s)));
  };
  if (two_levels) {
    detail::segment_on_support(down.points, down.pixels, cams, s, out, &sample.points);  // used with a plane only
    out.n_plane = out.n_plane - on_table + dropped;
  } else {
    detail::segment_voxelised(down.points, down.pixels, cams, s, plane, out);
  }
  out.seconds = since(t0);
  return out;
}

[[noreturn]] void bad(const std::string& m) { throw std::invalid_argument(m); }

void check_view(std::int64_t n_returns, const Eigen::Isometry3d& T, const char* what) {
  check_rigid(T, "T_world_camera");
  if (n_returns == 0) bad(std::string(what) + ": no pixel has a return (every depth is NaN, 0 or +inf)");
}

}  // namespace

int image_stride(const Eigen::Ref<const DepthImage>& depth, const PinholeCamera& camera,
                 const SegmentationSettings& s) {
  if (s.image_stride > 0) return s.image_stride;
  if (!(s.voxel_size > 0)) return 1;
  std::vector<double> z;  // the returns of every 4th pixel of every 4th row: the median to a fraction of a percent
  for (Eigen::Index v = 0; v < depth.rows(); v += 4)
    for (Eigen::Index u = 0; u < depth.cols(); u += 4)
      if (has_return(depth(v, u))) z.push_back(depth(v, u));
  if (z.empty()) return 1;
  auto mid = z.begin() + static_cast<std::ptrdiff_t>(z.size() / 2);
  std::nth_element(z.begin(), mid, z.end());
  // Pixels per half a voxel at the median depth: samples at most half a voxel apart put a point in every voxel a
  // surface crosses, so the voxel grid keeps the points (and the features and collision checks their density) of
  // segment_scene's on the same view. Blocks a whole voxel wide halved the objects' points and lost 4 points of
  // success on the development objects (one view, GMM, 300 attempts: 78.0% -> 73.7%, docs/one-view.md).
  const double side = 0.5 * s.voxel_size * std::min(camera.fx(), camera.fy()) / *mid;
  return std::max(1, static_cast<int>(std::floor(side)));
}

Segmentation segment_depth(const Eigen::Ref<const DepthImage>& depth, const PinholeCamera& camera,
                           const Eigen::Isometry3d& T_world_camera, const SegmentationSettings& settings,
                           const std::optional<Eigen::Vector4d>& plane) {
  const auto t0 = Clock::now();
  detail::check_segmentation_settings(settings);
  const std::int64_t n = camera.check_image(depth, "depth");
  check_view(n, T_world_camera, "depth");
  return segment_image(DepthPixels{depth, camera}, depth, camera, T_world_camera, settings, plane, t0, n);
}

namespace {

/// An organized cloud's depth image and its number of returns, checked (the row count, a rigid pose, a return).
struct OrganizedInput {
  DepthImage depth;
  std::int64_t n_returns = 0;
};

OrganizedInput checked_organized(const Eigen::Ref<const Vec3Array>& points, int height, int width,
                                 const Eigen::Isometry3d& T_world_camera) {
  OrganizedInput in{depth_of_organized(points, height, width, "points")};
  for (Eigen::Index r = 0; r < points.rows(); ++r) in.n_returns += points.row(r).allFinite() ? 1 : 0;
  check_view(in.n_returns, T_world_camera, "points");
  return in;
}

}  // namespace

Segmentation segment_organized(const Eigen::Ref<const Vec3Array>& points, int height, int width,
                               const Eigen::Isometry3d& T_world_camera, const SegmentationSettings& settings,
                               const std::optional<Eigen::Vector4d>& plane, double max_fit_rms) {
  const auto t0 = Clock::now();
  detail::check_segmentation_settings(settings);
  const OrganizedInput in = checked_organized(points, height, width, T_world_camera);
  const PinholeFit fit = fit_pinhole(points, height, width, max_fit_rms, "points");
  return segment_image(OrganizedPixels{points, width}, in.depth, fit.camera, T_world_camera, settings, plane, t0,
                       in.n_returns);
}

Segmentation segment_organized(const Eigen::Ref<const Vec3Array>& points, const PinholeCamera& camera,
                               const Eigen::Isometry3d& T_world_camera, const SegmentationSettings& settings,
                               const std::optional<Eigen::Vector4d>& plane) {
  const auto t0 = Clock::now();
  detail::check_segmentation_settings(settings);
  const OrganizedInput in = checked_organized(points, camera.height(), camera.width(), T_world_camera);
  return segment_image(OrganizedPixels{points, camera.width()}, in.depth, camera, T_world_camera, settings, plane, t0,
                       in.n_returns);
}

}  // namespace graspmix
