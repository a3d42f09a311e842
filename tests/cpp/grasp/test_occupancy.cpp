// The occupancy map against the analytic geometry of a box face seen by one camera, and the map baked from a
// visibility model against the rays' map and the exact geometry of a rendered box on a table.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "../perception/raycast.hpp"
#include "graspmix/grasp/occupancy.hpp"
#include "graspmix/perception/visibility.hpp"

using graspmix::CellState;
using graspmix::OccupancyMap;
using graspmix::OccupancySettings;
using graspmix::Vec3Array;

namespace {

const Eigen::Vector3d kCamera(-0.5, 0.0, 0.0);

/// What a camera at kCamera sees of the box [0, 0.1] x [-0.05, 0.05] x [-0.05, 0.05]: its face x = 0,
/// on a 2.5 mm grid.
Vec3Array seen_face() {
  Vec3Array out(41 * 41, 3);
  for (int j = 0; j <= 40; ++j)
    for (int k = 0; k <= 40; ++k) out.row(j * 41 + k) << 0.0, -0.05 + 0.0025 * j, -0.05 + 0.0025 * k;
  return out;
}

/// Where the camera's ray through p meets the plane x = 0 (p with x != camera's x).
Eigen::Vector2d on_face(const Eigen::Vector3d& p) {
  const Eigen::Vector3d d = p - kCamera;
  const Eigen::Vector3d hit = kCamera + d * (-kCamera.x() / d.x());
  return hit.tail<2>();
}

}  // namespace

TEST(Occupancy, FaceSeenFromOneSideFreeInFrontUnknownBehind) {
  const Vec3Array face = seen_face();
  const OccupancyMap map(face, kCamera.transpose(), face);
  const double h = map.resolution();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> ux(-0.09, 0.09), uyz(-0.06, 0.06);
  int n_front = 0, n_behind = 0;
  for (int i = 0; i < 20000; ++i) {
    const Eigen::Vector3d p(ux(rng), uyz(rng), uyz(rng));
    const Eigen::Vector2d f = on_face(p);
    // Inside the cone of rays by more than two cells' diagonals, at p's distance from the camera.
    const double lateral = (0.05 - f.cwiseAbs().maxCoeff()) * (p.x() - kCamera.x()) / -kCamera.x();
    if (lateral < 2 * std::sqrt(3.0) * h) continue;
    if (p.x() < -2 * h) {
      ++n_front;
      EXPECT_EQ(map.state(p), CellState::Free) << p.transpose();
    } else if (p.x() > 2 * h) {
      ++n_behind;
      EXPECT_EQ(map.state(p), CellState::Unknown) << p.transpose();
    }
  }
  EXPECT_GT(n_front, 1000);
  EXPECT_GT(n_behind, 1000);
  // The face's own cells are occupied; beside the box, where no ray went, unknown; outside the region free.
  EXPECT_EQ(map.state({0.001, 0.01, -0.02}), CellState::Occupied);
  EXPECT_EQ(map.state({0.05, 0.09, 0.0}), CellState::Unknown);
  EXPECT_EQ(map.state({0.3, 0.0, 0.0}), CellState::Free);
  EXPECT_GT(map.stats().n_rays, 0);
  EXPECT_EQ(map.stats().n_free + map.stats().n_occupied + map.stats().n_unknown,
            static_cast<std::int64_t>(map.dims().cast<double>().prod()));
}

TEST(Occupancy, AnyBlockedAgreesWithEveryCellOfTheBox) {
  const Vec3Array face = seen_face();
  const OccupancyMap map(face, kCamera.transpose(), face);
  const double h = map.resolution();
  const Eigen::Vector3d lo = map.region_min(), hi = map.region_max();
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0), size(0.0, 0.04);
  int n_true = 0, n_false = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    // Boxes around the region, some reaching past it (cells outside it are free).
    Eigen::Vector3d a, b;
    for (int d = 0; d < 3; ++d) {
      a[d] = lo[d] - 0.03 + (hi[d] - lo[d] + 0.06) * u(rng);
      b[d] = a[d] + size(rng);
    }
    bool brute = false;  // every cell centre the box's cells hold, by the map's own lookup
    const Eigen::Vector3d first = ((a - lo) / h).array().floor(), last = ((b - lo) / h).array().floor();
    for (double i = first.x(); i <= last.x() && !brute; ++i)
      for (double j = first.y(); j <= last.y() && !brute; ++j)
        for (double k = first.z(); k <= last.z() && !brute; ++k)
          brute = map.blocked(map.state(lo + h * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5)));
    EXPECT_EQ(map.any_blocked(a, b), brute) << a.transpose() << " / " << b.transpose();
    (brute ? n_true : n_false) += 1;
  }
  EXPECT_GT(n_true, 300);
  EXPECT_GT(n_false, 300);
}

TEST(Occupancy, CellsWithinOneCellOfThePlaneAreFree) {
  const Vec3Array face = seen_face();
  // The box stands on z = -0.05; the plane is given upside down and oriented towards the camera.
  const OccupancyMap map(face, kCamera.transpose(), face, Eigen::Vector4d(0, 0, -1, -0.05));
  EXPECT_NEAR(map.plane()[2], 1.0, 1e-12);
  const double h = map.resolution();
  EXPECT_EQ(map.state({0.05, 0.0, -0.05 + 0.5 * h}), CellState::Free);  // the table's layer: the plane's term
  EXPECT_EQ(map.state({0.05, 0.0, -0.05 - 0.02}), CellState::Free);     // below the table
  EXPECT_EQ(map.state({0.05, 0.0, -0.03}), CellState::Unknown);         // the shadow above it
}

TEST(Occupancy, BadInputThrows) {
  const Vec3Array face = seen_face();
  const Eigen::RowVector3d cam = kCamera.transpose();
  OccupancySettings s;
  s.resolution = 0.0;
  EXPECT_THROW(OccupancyMap(face, cam, face, std::nullopt, s), std::invalid_argument);
  s.resolution = -0.005;
  EXPECT_THROW(OccupancyMap(face, cam, face, std::nullopt, s), std::invalid_argument);
  s = OccupancySettings{};
  s.margin = -1;
  EXPECT_THROW(OccupancyMap(face, cam, face, std::nullopt, s), std::invalid_argument);
  s = OccupancySettings{};
  s.max_cells = 1000;
  EXPECT_THROW(OccupancyMap(face, cam, face, std::nullopt, s), std::invalid_argument);
  const Eigen::RowVector3d nan(std::numeric_limits<double>::quiet_NaN(), 0, 0);
  EXPECT_THROW(OccupancyMap(face, nan, face), std::invalid_argument);
  Vec3Array bad_points = face;
  bad_points(3, 1) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(OccupancyMap(bad_points, cam, face), std::invalid_argument);
  EXPECT_THROW(OccupancyMap(Vec3Array(0, 3), cam, face), std::invalid_argument);
  EXPECT_THROW(OccupancyMap(face, Vec3Array(2, 3), face), std::invalid_argument);  // neither 1 nor N rows
  // A camera inside the objects' box (a cloud in its sensor's frame given without its viewpoint).
  Vec3Array box = face;
  box.col(0).setLinSpaced(0.0, 0.1);
  EXPECT_THROW(OccupancyMap(box, Eigen::RowVector3d(0.05, 0, 0), box), std::invalid_argument);
  EXPECT_THROW(OccupancyMap(face, cam, face, Eigen::Vector4d(0, 0, 0, 1)), std::invalid_argument);
}

namespace {

// A 320 x 240 camera 55 cm from a box on the table z = 0 (a pixel is about 2 mm there, under half a cell).
const graspmix::PinholeCamera kView(262.5, 262.5, 159.5, 119.5, 320, 240);
const Eigen::Isometry3d kViewPose = graspmix::test::looking_at({0.0, -0.40, 0.38}, {0.0, 0.0, 0.05});
const Eigen::Vector3d kLo(-0.04, -0.03, 0.0), kHi(0.04, 0.03, 0.10);
const Eigen::Vector4d kTable(0, 0, 1, 0);

double box_and_table(const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  return std::min(graspmix::test::hit_box(o, d, kLo, kHi),
                  graspmix::test::hit_plane(o, d, Eigen::Vector3d::UnitZ(), 0.0));
}

/// Whether the ray o + t d meets the box before the table.
bool on_the_box(const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  return graspmix::test::hit_box(o, d, kLo, kHi) <= graspmix::test::hit_plane(o, d, Eigen::Vector3d::UnitZ(), 0.0);
}

/// The image's points in the world (table included) and the box's (those above the table).
std::pair<Vec3Array, Vec3Array> view_points(const graspmix::DepthImage& image) {
  std::vector<Eigen::Vector3d> all, box;
  for (int v = 0; v < image.rows(); ++v)
    for (int u = 0; u < image.cols(); ++u) {
      const Eigen::Vector3d p = kViewPose * kView.back_project(u, v, image(v, u));
      all.push_back(p);
      if (p.z() > 1e-6) box.push_back(p);
    }
  auto to_array = [](const std::vector<Eigen::Vector3d>& pts) {
    Vec3Array out(static_cast<Eigen::Index>(pts.size()), 3);
    for (size_t i = 0; i < pts.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = pts[i].transpose();
    return out;
  };
  return {to_array(all), to_array(box)};
}

}  // namespace

TEST(Occupancy, FromVisibilityAgreesWithTheRaysAndTheExactGeometry) {
  const graspmix::DepthImage image = graspmix::test::render(kView, kViewPose, box_and_table);
  const auto [points, box] = view_points(image);
  const graspmix::VisibilityModel vis = graspmix::VisibilityModel::from_depth(image, kView, kViewPose);
  const OccupancyMap from_vis(vis, box, kTable);
  const OccupancyMap rays(points, kViewPose.translation().transpose(), box, kTable);
  // The same region, cell for cell.
  ASSERT_TRUE(from_vis.region_min().isApprox(rays.region_min()));
  ASSERT_EQ(from_vis.dims(), rays.dims());
  EXPECT_EQ(from_vis.stats().n_free + from_vis.stats().n_occupied + from_vis.stats().n_unknown,
            std::int64_t{from_vis.dims().prod()});
  const double h = from_vis.resolution();
  const Eigen::Vector3d eye = kViewPose.translation();
  const Eigen::Vector3i d = from_vis.dims();
  int n_agree = 0, n_cells = 0, n_free = 0, n_unseen = 0;
  for (int k = 0; k < d.z(); ++k)
    for (int j = 0; j < d.y(); ++j)
      for (int i = 0; i < d.x(); ++i) {
        const Eigen::Vector3d c = from_vis.region_min() + h * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5);
        const CellState a = from_vis.state(c), b = rays.state(c);
        ++n_cells;
        n_agree += a == b;
        if (c.z() < h) {  // the table's layer and below: free in both (the plane's own term)
          EXPECT_EQ(a, CellState::Free);
          EXPECT_EQ(b, CellState::Free);
          continue;
        }
        // The exact answer where it is unambiguous: the rays through the cell's centre and its corners meet the
        // same surface within a cell (no silhouette across the cell), and the centre lies well in front of it
        // (free) or well behind it (unseen), along its ray.
        const Eigen::Vector3d ray = c - eye;
        const double t_centre = box_and_table(eye, ray.normalized());
        const bool on_box = on_the_box(eye, ray.normalized());
        double t_min = t_centre, t_max = t_centre;
        bool one_surface = std::isfinite(t_centre);
        for (int corner = 0; corner < 8; ++corner) {
          const Eigen::Vector3d q =
              c + 0.5 * h * Eigen::Vector3d(corner & 1 ? 1 : -1, corner & 2 ? 1 : -1, corner & 4 ? 1 : -1);
          const Eigen::Vector3d dir = (q - eye).normalized();
          const double t = box_and_table(eye, dir);
          one_surface = one_surface && std::isfinite(t) && on_the_box(eye, dir) == on_box;
          t_min = std::min(t_min, t);
          t_max = std::max(t_max, t);
        }
        if (!one_surface) continue;
        const double tol = vis.settings().surface_tolerance;
        if (ray.norm() < t_min - 2 * h) {
          ++n_free;
          EXPECT_EQ(a, CellState::Free) << c.transpose();
          EXPECT_EQ(b, CellState::Free) << c.transpose();
        } else if (ray.norm() > t_max + tol + 2 * h) {
          ++n_unseen;
          EXPECT_EQ(a, CellState::Unknown) << c.transpose();
          EXPECT_EQ(b, CellState::Unknown) << c.transpose();
        }
      }
  EXPECT_GT(n_free, 50000);   // 103.6k of the 181k cells at the time of writing
  EXPECT_GT(n_unseen, 3000);  // 6.7k
  // Everywhere, ambiguous cells included (silhouettes, the surface's own cells): 99.4% agree at the time of writing.
  EXPECT_GT(static_cast<double>(n_agree) / n_cells, 0.98) << n_agree << " of " << n_cells;
  // A model of no view, no object point, a non-finite one: errors.
  EXPECT_THROW(OccupancyMap(graspmix::VisibilityModel{}, box, kTable), std::invalid_argument);
  EXPECT_THROW(OccupancyMap(vis, Vec3Array(0, 3), kTable), std::invalid_argument);
  Vec3Array bad = box;
  bad(0, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(OccupancyMap(vis, bad, kTable), std::invalid_argument);
  EXPECT_THROW(OccupancyMap(vis, box, Eigen::Vector4d::Zero()), std::invalid_argument);
}

TEST(Occupancy, FromVisibilityLeavesWhatNoViewSawFreeAndTheShadowUnknown) {
  // An unorganized cloud of a box's face cropped to the box (no table): the spherical view's bins around the face are
  // empty. Only the shadow behind the face is unknown; beside it no view says anything, which is not an obstacle.
  const Vec3Array face = seen_face();
  const graspmix::VisibilityModel vis = graspmix::VisibilityModel::from_points(face, kCamera);
  const OccupancyMap map(vis, face);
  EXPECT_EQ(map.state({0.05, 0.0, 0.0}), CellState::Unknown);  // behind the face, in the box
  EXPECT_EQ(map.state({-0.05, 0.0, 0.0}), CellState::Free);    // in front of it: seen free
  EXPECT_EQ(map.state({0.05, 0.09, 0.0}), CellState::Free);    // beside the box: no view says anything
  EXPECT_TRUE(std::isnan(vis.signed_distance({0.05, 0.09, 0.0})));
  // The rays' map calls that unknown: no ray crossed it.
  EXPECT_EQ(OccupancyMap(face, kCamera.transpose(), face).state({0.05, 0.09, 0.0}), CellState::Unknown);
}
