#pragma once
// The object representation O(v, r) of the paper ("The object representation", Fig.
// point_cloud_and_feat): every point carries an outward unit normal, the principal curvatures
// r = [k1, k2] of PCL's PrincipalCurvaturesEstimation and a right-handed frame v = (p, q) with
// z = outward normal, x = first principal direction, y = z x x.
//
// k1, k2 are PCL's pc1, pc2: eigenvalues of the covariance of the neighbours' normals projected on
// the tangent plane. They are dimensionless and depend on the radius: on a sphere of radius R,
// k1 ~ k2 ~ (radius / 2R)^2; on a cylinder k1 ~ (radius / 2R)^2, k2 ~ 0; on a plane both ~ 0.
// Demonstration and query clouds must use the same radius and sampling density.
//
// Normals follow PCL's NormalEstimation (smallest eigenvector of the covariance of the neighbours
// within radius, computed here in double); curvatures are PCL's PrincipalCurvaturesEstimation run
// per point, one estimator per OpenMP thread. Neighbours come from a uniform grid over the points
// in a canonical order, so results are bit-identical for any permutation of the input and any
// thread count.
//
// Where k1 ~ k2 (spheres, planes) the principal direction is noise, so the frame's x axis is
// chosen deterministically from the normal instead (see SurfaceFeatureSettings and `isotropic`):
// x = the world z axis projected on the tangent plane, or the world x axis where the normal is
// within ~26 degrees of +-z. The sign of a used principal direction is fixed by the same rule
// (x . reference >= 0), so frames never depend on the eigen-solver's sign or the point order.
#include <cstddef>
#include <string>

#include <Eigen/Core>

#include "graspmix/core/types.hpp"

namespace graspmix {

/// How normals are turned outward.
enum class NormalOrientation {
  Auto,       ///< towards the viewpoints when given; else given normals as they are; else Propagate
  Viewpoint,  ///< towards the viewpoint(s): right for clouds seen by cameras
  Propagate,  ///< outward at the point farthest from the centroid, then propagated along a minimum
              ///< spanning tree of the k-nearest-neighbour graph (Hoppe et al. 1992); concave parts
              ///< (a torus's inside, a cup's inner wall) come out right as long as walls are thicker
              ///< than the radius. A thinner wall is not resolved by radius-sized normals at all: its
              ///< two sides get the same normal, so give viewpoints or normals for such objects.
  Centroid,   ///< away from the centroid: only for star-shaped (e.g. convex) objects
  AsGiven,    ///< keep the signs of the given normals
};

struct SurfaceFeatureSettings {
  double radius = 0.01;     ///< neighbourhood radius of normals and curvatures (m); paper: 1 cm
  int min_neighbours = 10;  ///< points with fewer neighbours within radius (itself included) are dropped
  /// The principal direction is used for x only where (k1 - k2) / k1 >= min_anisotropy ...
  double min_anisotropy = 0.25;
  double flat_curvature = 1e-4;  ///< ... and k1 >= flat_curvature (dimensionless, like k1)
  NormalOrientation orientation = NormalOrientation::Auto;
  int orientation_neighbours = 10;  ///< k of the propagation graph
  int n_threads = 0;                ///< 0 = OpenMP's default, else 1..kMaxFeatureThreads; results do not depend on it
  /// A neighbourhood (within radius) holding more points than this is refused (0: no cap): the cloud is
  /// far denser than the radius needs, and every stage costs time per neighbour (2M points on a 5 cm
  /// sphere hold ~20k each, which runs for tens of minutes). Voxel-downsample such a cloud first; with
  /// the paper's 1 cm radius ordinary clouds hold up to a few hundred, so the cap never changes a result.
  int max_neighbours = 5000;
};

/// The largest SurfaceFeatureSettings::n_threads.
inline constexpr int kMaxFeatureThreads = 256;

/// O(v, r) for the kept points; row i of every array describes the same point.
struct SurfaceCloud {
  Vec3Array points;                                                      ///< (N, 3) metres
  Vec3Array normals;                                                     ///< (N, 3) unit, outward
  Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor> curvatures;  ///< (N, 2) [k1, k2], k1 >= k2 >= 0
  PoseArray frames;            ///< (N, 7) T_world_feature [x, y, z, qx, qy, qz, qw], qw >= 0
  Eigen::VectorXi indices;     ///< (N) the input row of every kept point
  Eigen::VectorXi neighbours;  ///< (N) neighbours within radius, itself included
  /// (N) true where x came from the deterministic rule (k1 ~ k2 or flat), not from PCL's direction.
  Eigen::Matrix<bool, Eigen::Dynamic, 1> isotropic;
  /// (N) radians: how undetermined the rotation about the normal is, pi exp(-100 ((k1 - k2) / k1)^2)
  /// as in Kopicki's Golem (pi where k1 = 0). A sampler can rotate frames about z by up to this.
  Eigen::VectorXd frame_ambiguity;
  std::size_t n_input = 0;    ///< points given
  std::size_t n_dropped = 0;  ///< points dropped (too few neighbours, or no finite estimate)
  double radius = 0.0;        ///< the radius used (m)
  std::string orientation;    ///< the rule that oriented the normals: given|viewpoint|propagate|centroid
  double seconds_normals = 0.0, seconds_orientation = 0.0, seconds_curvatures = 0.0, seconds_total = 0.0;
};

/// O(v, r) of a cloud. points (N, 3) finite. normals: empty, or (N, 3) to use instead of estimating
/// them. viewpoints: empty, (1, 3) for every point or (N, 3) one per point (the camera that saw it).
/// Throws std::invalid_argument on bad input (non-finite points, settings out of range, a cloud whose
/// points all coincide), when a neighbourhood exceeds max_neighbours, and when no point has a stable
/// neighbourhood (too few neighbours, or every neighbourhood degenerate: its points coincide or lie on
/// one line, so no plane is defined): degenerate input is an error, never an empty or made-up result.
SurfaceCloud compute_surface_features(const Vec3Array& points, const SurfaceFeatureSettings& settings = {},
                                      const Vec3Array& normals = {}, const Vec3Array& viewpoints = {});

/// The frame (N, 7) of points with unit normals and principal directions (N, 3); rows where
/// `isotropic` is true (or the direction is degenerate) take the deterministic x described above.
PoseArray surface_frames(const Vec3Array& points, const Vec3Array& normals, const Vec3Array& directions,
                         const Eigen::Matrix<bool, Eigen::Dynamic, 1>& isotropic);

NormalOrientation normal_orientation_from_string(const std::string& name);
std::string to_string(NormalOrientation o);

}  // namespace graspmix
